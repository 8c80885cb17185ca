#pragma once
// Force-included (-include) into the clang fuzz build only. Debian 12's clang 14 lacks
// __builtin_source_location, so libstdc++ 12's <source_location> declares nothing and
// penumbra/Error.h would not compile. This stand-in reports no location, which the loaders never
// read (their messages carry the file and field); GCC builds never see it.
#include <version>
#if !defined(__cpp_lib_source_location)
#include <cstdint>
namespace std {
struct source_location {
  static constexpr source_location current() noexcept { return {}; }
  constexpr uint_least32_t line() const noexcept { return 0; }
  constexpr uint_least32_t column() const noexcept { return 0; }
  constexpr const char* file_name() const noexcept { return ""; }
  constexpr const char* function_name() const noexcept { return ""; }
};
}  // namespace std
#endif
