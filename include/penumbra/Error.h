#pragma once
// Penumbra's error policy (STYLE.md):
//  - PN_ASSERT: programmer mistakes, checked in debug builds only.
//  - PN_CHECK / penumbra::Error: runtime failures (bad input, files, shader compile, GL features).
//    The CLI turns an Error into one line on stderr and a non-zero exit.
#include <cassert>
#include <source_location>
#include <stdexcept>
#include <string>

namespace penumbra {

/// What kind of failure; the CLI maps Usage to exit code 2 and everything else to 1.
enum class ErrorKind { Runtime, Usage };

class Error : public std::runtime_error {
public:
  explicit Error(const std::string& message, ErrorKind kind = ErrorKind::Runtime,
                 std::source_location where = std::source_location::current())
      : std::runtime_error(message), mKind(kind), mWhere(where) {}
  ErrorKind kind() const { return mKind; }
  const std::source_location& where() const { return mWhere; }

private:
  ErrorKind mKind;
  std::source_location mWhere;
};

/// A bad command line or parameter: exit code 2.
inline Error usageError(const std::string& message) { return Error(message, ErrorKind::Usage); }

}  // namespace penumbra

#define PN_ASSERT(cond) assert(cond)
#define PN_CHECK(cond, message)                                           \
  do {                                                                    \
    if (!(cond)) throw ::penumbra::Error(std::string(message));           \
  } while (false)
