#include "bench/ScaleBench.h"

#include "platform/Context.h"

#include <penumbra/Error.h>
#include <penumbra/Reference.h>
#include <penumbra/Renderer.h>
#include <penumbra/SceneIO.h>
#include <penumbra/Technique.h>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace penumbra::report {
namespace {

constexpr double kGridSizeM = 100.0;
// The height field's waves (m and 1/m): enough relief for the sun to cast shadows on the grid.
constexpr double kWaveHeightM = 1.5, kWaveX = 0.13, kWaveZ = 0.21;

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::string esc(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

}  // namespace

int scaleGridCells(double millions) { return std::max(1, static_cast<int>(std::lround(std::sqrt(millions * 1e6 / 2.0)))); }

void writeScaleGrid(const std::filesystem::path& path, int cells) {
  std::ofstream out(path, std::ios::binary);
  PN_CHECK(out, fmt::format("cannot write {}", path.string()));
  const int n = cells, row = n + 1;
  std::string text = fmt::format("# penumbra bench: a {} x {} height-field grid and a box\no grid\n", n, n);
  auto flush = [&] {
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    text.clear();
  };
  for (int j = 0; j <= n; ++j) {
    const double z = kGridSizeM * (static_cast<double>(j) / n - 0.5), wz = std::sin(z * kWaveZ);
    for (int i = 0; i <= n; ++i) {
      const double x = kGridSizeM * (static_cast<double>(i) / n - 0.5);
      text += fmt::format("v {:.4f} {:.4f} {:.4f}\n", x, kWaveHeightM * std::sin(x * kWaveX) * wz, z);
    }
    flush();
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * row + i + 1;  // OBJ counts from 1
      text += fmt::format("f {} {} {}\nf {} {} {}\n", a, a + row, a + 1, a + 1, a + row, a + row + 1);
    }
    flush();
  }
  const int first = row * row + 1;
  text += "o box\n";
  for (double y : {3.0, 13.0})
    for (auto [x, z] : {std::pair{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}) text += fmt::format("v {} {} {}\n", x, y, z);
  for (auto q : {std::array{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}})
    text += fmt::format("f {} {} {} {}\n", first + q[0], first + q[1], first + q[2], first + q[3]);
  flush();
  PN_CHECK(out.good(), fmt::format("cannot write {}", path.string()));
}

std::vector<ScaleRow> runScalePlan(gl::Context& /*current*/, const std::vector<double>& millions, const BenchSettings& settings,
                                   const std::filesystem::path& workDir, bool progress) {
  std::vector<ScaleRow> rows;
  std::filesystem::create_directories(workDir);
  for (double m : millions) {
    ScaleRow row;
    const int cells = scaleGridCells(m);
    const std::filesystem::path obj = workDir / fmt::format("scale-grid-{}.obj", cells);
    try {
      writeScaleGrid(obj, cells);
      row.fileBytes = std::filesystem::file_size(obj);
      auto start = std::chrono::steady_clock::now();
      LoadOptions load;
      load.referenceBvh = true;
      Scene scene = loadScene(obj.string(), load);
      row.loadSeconds = seconds(start);
      std::filesystem::remove(obj);
      for (const Mesh& mesh : scene.meshes) row.vertices += mesh.vertexCount();
      row.triangles = scene.triangleCount();
      const int mapSize = settings.shadowMapSize.value_or(scene.shadow.mapSize);
      Renderer renderer;
      renderer.setScene(std::move(scene));
      renderer.setTechnique(Technique("uniform", "hard").setMapSize(mapSize));
      RenderOptions render;
      render.width = settings.width;
      render.height = settings.height;
      for (int f = 0; f < settings.warmupFrames; ++f) renderer.render(render);
      std::vector<double> gbuffer, shadow;
      for (int f = 0; f < settings.timedFrames; ++f) {
        renderer.render(render);
        gbuffer.push_back(renderer.timings().get("gbuffer"));
        shadow.push_back(renderer.timings().get("shadow"));
      }
      row.frames = settings.timedFrames;
      row.gbufferMs = timeStats(gbuffer);
      row.shadowMs = timeStats(shadow);
      const ReferenceTracer tracer(renderer.scene(), MeshStorage::Borrowed);
      row.bvhSeconds = tracer.bvhBuildSeconds();
      row.bvhBytes = tracer.bvhBytes();
      row.bvhPeakBytes = tracer.bvhPeakBytes();
    } catch (const std::exception& e) {
      row.error = e.what();
      std::error_code ec;
      std::filesystem::remove(obj, ec);
    }
    if (progress)
      std::fprintf(stderr, "bench: scale %.1f M triangles: %s\n", static_cast<double>(row.triangles) / 1e6,
                   row.error.empty() ? fmt::format("gbuffer {:.1f} ms, shadow {:.1f} ms, BVH {:.1f} s", row.gbufferMs.median,
                                                   row.shadowMs.median, row.bvhSeconds).c_str()
                                     : row.error.c_str());
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string scaleSectionHtml(const std::vector<ScaleRow>& rows, const MachineInfo& machine) {
  if (rows.empty()) return "";
  std::string h = "<h3 id=\"scale\">Cost against triangle count</h3>\n";
  h += fmt::format(
      "<p class=\"note\">A height-field grid of 2&thinsp;N² triangles and a box, loaded from OBJ, rendered with hard shadows "
      "and the uniform projection; pass times are medians over the timed frames ({}, {}), the BVH is the reference's "
      "(Embree's own allocations). Per triangle: each pass's median over the triangle count.</p>\n",
      esc(machine.glRenderer), esc(machine.clock));
  h += "<table><tr><th>triangles</th><th>vertices</th><th>OBJ MiB</th><th>load s</th><th>load s/MiB</th>"
       "<th>G-buffer ms</th><th>G-buffer ns/tri</th><th>shadow ms</th><th>shadow ns/tri</th><th>BVH build s</th>"
       "<th>BVH MiB</th><th>BVH peak MiB</th><th>BVH B/tri</th></tr>\n";
  for (const ScaleRow& r : rows) {
    if (!r.error.empty()) {
      h += fmt::format("<tr><td>{:.2f} M</td><td class=\"l why\" colspan=\"12\"><b>failed</b>: {}</td></tr>\n",
                       static_cast<double>(r.triangles) / 1e6, esc(r.error));
      continue;
    }
    const double tri = static_cast<double>(r.triangles);
    h += fmt::format("<tr><td>{:.2f} M</td><td>{:.2f} M</td><td>{:.0f}</td><td>{:.2f}</td><td>{:.4f}</td><td>{:.1f}</td><td>{:.1f}</td>"
                     "<td>{:.1f}</td><td>{:.1f}</td><td>{:.2f}</td><td>{:.0f}</td><td>{:.0f}</td><td>{:.0f}</td></tr>\n",
                     tri / 1e6, static_cast<double>(r.vertices) / 1e6, static_cast<double>(r.fileBytes) / kBytesPerMiB, r.loadSeconds,
                     r.loadSecondsPerMiB(), r.gbufferMs.median, r.gbufferNsPerTriangle(), r.shadowMs.median, r.shadowNsPerTriangle(),
                     r.bvhSeconds, static_cast<double>(r.bvhBytes) / kBytesPerMiB, static_cast<double>(r.bvhPeakBytes) / kBytesPerMiB,
                     static_cast<double>(r.bvhPeakBytes) / tri);
  }
  h += "</table>\n";
  // Linearity: each pass's cost per triangle at the largest count against the smallest.
  const ScaleRow *lo = nullptr, *hi = nullptr;
  for (const ScaleRow& r : rows)
    if (r.error.empty()) {
      if (!lo || r.triangles < lo->triangles) lo = &r;
      if (!hi || r.triangles > hi->triangles) hi = &r;
    }
  if (lo && hi && lo != hi) {
    const double growth = static_cast<double>(hi->triangles) / static_cast<double>(lo->triangles);
    h += fmt::format("<p class=\"note\">From {:.1f} M to {:.1f} M triangles (×{:.1f}): G-buffer ×{:.2f}, shadow ×{:.2f}, "
                     "BVH build ×{:.2f}, load ×{:.2f} (×{:.1f} would be linear).</p>\n",
                     static_cast<double>(lo->triangles) / 1e6, static_cast<double>(hi->triangles) / 1e6, growth,
                     hi->gbufferMs.median / lo->gbufferMs.median, hi->shadowMs.median / lo->shadowMs.median,
                     hi->bvhSeconds / lo->bvhSeconds, hi->loadSeconds / lo->loadSeconds, growth);
  }
  return h;
}

}  // namespace penumbra::report
