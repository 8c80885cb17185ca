// The field a JSON text stops parsing at (JsonProblem.h): nlohmann's SAX interface walked with a
// stack of the objects' keys and the arrays' indices, read when its parse_error arrives.
#include "sceneio/JsonProblem.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <vector>

namespace penumbra::sceneio {
namespace {

using Json = nlohmann::json;

class PlaceTracker : public nlohmann::json_sax<Json> {
public:
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    mStack.push_back({false, 0, ""});
    return true;
  }
  bool key(string_t& k) override {
    mStack.back().key = k;
    return true;
  }
  bool end_object() override {
    mStack.pop_back();
    return value();
  }
  bool start_array(std::size_t) override {
    mStack.push_back({true, 0, ""});
    return true;
  }
  bool end_array() override {
    mStack.pop_back();
    return value();
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    const std::string at = place();
    mProblem = at.empty() ? cleaned(e.what()) : fmt::format("{}: {}", at, cleaned(e.what()));
    return false;
  }
  const std::string& problem() const { return mProblem; }

private:
  struct Level {
    bool array;
    size_t index;     // array: the element being read
    std::string key;  // object: the member being read
  };

  bool value() {
    if (!mStack.empty() && mStack.back().array) ++mStack.back().index;
    return true;
  }
  std::string place() const {
    std::string p;
    for (const Level& l : mStack) {
      if (l.array) p += fmt::format("[{}]", l.index);
      else if (!l.key.empty()) p += (p.empty() ? "" : ".") + l.key;
    }
    return p;
  }
  /// nlohmann's message without its "[json.exception…] " tag and the "; last read: …" bytes.
  static std::string cleaned(std::string what) {
    if (const size_t tag = what.find("] "); what.rfind("[json.exception.", 0) == 0 && tag != std::string::npos) what.erase(0, tag + 2);
    if (const size_t bytes = what.find("; last read:"); bytes != std::string::npos) what.erase(bytes);
    return what;
  }

  std::vector<Level> mStack;
  std::string mProblem;
};

}  // namespace

std::string jsonParseProblem(std::span<const uint8_t> text) {
  PlaceTracker tracker;
  Json::sax_parse(text.begin(), text.end(), &tracker);
  return tracker.problem();
}

}  // namespace penumbra::sceneio
