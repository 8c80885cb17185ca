#pragma once
// The bench's triangle-count plan: what a scene's size costs. For each count, a height-field grid
// of 2 N² triangles (shared vertices, as the OBJ loader keeps them) with a box standing on it is
// written as an OBJ file and loaded as `--scene grid.obj` would be (load time per MB), rendered
// with hard shadows and the uniform projection (the G-buffer and shadow passes' median times per
// triangle), and given to the reference (the Embree BVH's build time and memory: Embree's own
// allocations, at their peak during the build and once built). docs/bench.md#scale.
#include "bench/BenchPlan.h"
#include "bench/BenchResults.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::gl { class Context; }

namespace penumbra::report {

/// Millions of grid triangles of the default plan.
inline const std::vector<double> kDefaultScalePlan = {0.5, 2.0, 8.0};

/// Writes the plan's grid of `cells` × `cells` quads (2 cells² triangles over a 100 m square) and
/// the box as an OBJ file.
void writeScaleGrid(const std::filesystem::path& path, int cells);

/// Cells per side for about `millions` million grid triangles.
int scaleGridCells(double millions);

/// Runs the plan at settings' image and map size (the scene's own map size when unset), timing
/// settings.timedFrames frames after settings.warmupFrames; the OBJ files go to `workDir` and are
/// removed after loading. `progress`: one line per count on stderr.
std::vector<ScaleRow> runScalePlan(gl::Context& context, const std::vector<double>& millions, const BenchSettings& settings,
                                   const std::filesystem::path& workDir, bool progress);

/// The report's section on the plan ("" when the run had none): a table per count, the cost per
/// triangle, and where a pass does not grow linearly.
std::string scaleSectionHtml(const std::vector<ScaleRow>& rows, const MachineInfo& machine);

}  // namespace penumbra::report
