#pragma once
// Where a JSON text stops parsing, as a field path: "lights[1].intensity: number overflow
// parsing '1e400'". A scene or glTF file that a tool wrote with NaN or Infinity (Python's json
// module does) or a number past a double's range is then named by its field, as every other bad
// value is.
#include <cstdint>
#include <span>
#include <string>

namespace penumbra::sceneio {

/// Why `text` is not valid JSON, prefixed with the field being read when parsing stopped
/// ("lights[1].intensity: …"; no prefix outside every object's members) and without the bytes
/// the parser last read (they echo whatever the file holds). "" when `text` parses.
std::string jsonParseProblem(std::span<const uint8_t> text);

}  // namespace penumbra::sceneio
