// The --camera argument: a camera as "X,Y,Z:TX,TY,TZ:FOV" (metres, degrees), parsed and written.
#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <charconv>
#include <cmath>
#include <vector>

namespace penumbra {

Camera parseCameraArgument(const std::string& text, const Camera& base) {
  const auto fail = [&](const std::string& why) {
    return usageError(fmt::format("--camera {}: {} (expected X,Y,Z:TX,TY,TZ[:FOV], e.g. 4,3,6:0,0.5,0:40)", text, why));
  };
  std::vector<std::string> groups(1);
  for (char c : text) {
    if (c == ':') groups.emplace_back();
    else groups.back() += c;
  }
  if (groups.size() < 2 || groups.size() > 3) throw fail("expected two or three ':'-separated parts");
  const auto number = [&](const std::string& s) {
    float v = 0.0f;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
      throw fail(fmt::format("'{}' is not a finite number", s));
    return v;
  };
  const auto point = [&](const std::string& s, const char* what) {
    glm::vec3 p(0.0f);
    size_t start = 0;
    for (int i = 0; i < 3; ++i) {
      const size_t comma = s.find(',', start);
      if ((i < 2) != (comma != std::string::npos)) throw fail(fmt::format("the {} needs three numbers", what));
      p[i] = number(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
      if (std::abs(p[i]) > kMaxCoordinateM) throw fail(fmt::format("{} {} is beyond ±1e6 m", what, p[i]));
      start = comma + 1;
    }
    return p;
  };
  Camera c = base;
  c.position = point(groups[0], "position");
  c.target = point(groups[1], "target");
  if (const std::string problem = c.viewProblem(); !problem.empty()) throw fail(problem);
  if (groups.size() == 3) {
    const float fovDeg = number(groups[2]);
    if (fovDeg < 1.0f || fovDeg > 170.0f) throw fail(fmt::format("field of view {}° is outside 1–170°", fovDeg));
    c.fovYRad = glm::radians(fovDeg);
  }
  return c;
}

std::string cameraArgument(const Camera& camera) {
  const glm::vec3 p = camera.position, t = camera.target;
  return fmt::format("{},{},{}:{},{},{}:{}", p.x, p.y, p.z, t.x, t.y, t.z, glm::degrees(camera.fovYRad));
}

}  // namespace penumbra
