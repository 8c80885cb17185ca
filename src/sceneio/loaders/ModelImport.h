#pragma once
// Model files (glTF 2.0 .gltf/.glb, Wavefront .obj) as scenes or as parts of a scene file.
// Every loader enforces the limits below and reports any bad input as one penumbra::Error,
// "model.glb: accessors[3]: index 812 is out of range (600 vertices)": the file, the field, the
// problem. The limits are documented in docs/scenes.md; change both together.
#include <penumbra/Scene.h>
#include <penumbra/SceneIO.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::loaders {

// --- limits (docs/scenes.md) ---------------------------------------------------------------
/// Largest file read (model, .bin buffer, .mtl, image): keeps a typo'd path (a disk image, a
/// device) from being slurped into memory.
inline constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;
/// How many vertices and triangles a scene may have is set by memory, not by a count: see
/// SceneCounts and checkSceneMemory below.
/// Placed meshes (one draw call each).
inline constexpr uint64_t kMaxObjects = uint64_t(1) << 16;
/// glTF node hierarchy depth; real files stay below 30, a recursion guard needs some bound.
inline constexpr int kMaxNodeDepth = 256;
/// JSON nesting depth of a glTF document (the format itself needs about 8; `extras` may nest more).
inline constexpr int kMaxJsonDepth = 64;
/// Images: count, side in texels, and decoded RGBA8 bytes of all images together.
inline constexpr uint64_t kMaxImages = 1024;
inline constexpr int kMaxImageSide = 8192;
inline constexpr uint64_t kMaxImageBytes = uint64_t(1) << 30;

/// Default light and camera placed when a model file has none (docs/scenes.md).
inline constexpr float kDefaultSunAngularRadiusRad = 0.00465f;  // the real sun's angular radius

// --- API ------------------------------------------------------------------------------------
/// A loaded model: its meshes, materials, images, objects (world transforms from the file's own
/// hierarchy) and any lights/camera it defines.
struct Model {
  Scene scene;             ///< no default light or camera added
  bool hasCamera = false;  ///< scene.camera came from the file
};

/// True when the extension names a model format (.gltf, .glb, .obj; any case).
bool isModelFile(const std::filesystem::path& path);

/// Loads a .gltf, .glb or .obj file. Throws Error("file: field: problem") on any bad input, and
/// when no triangle it places has an area (nothing would be drawn).
Model loadModelFile(const std::filesystem::path& path, const LoadOptions& options = {});

/// Loads a model file as a complete scene: adds a sun from a default direction when it has no
/// light and a camera framing its bounds when it has none, then validates it.
Scene loadModelScene(const std::filesystem::path& path, const LoadOptions& options = {});

/// Reports a model file's progress through options.progress (nothing when it is empty), at most
/// every kProgressStep of the work so that a million-element loop costs nothing.
class ProgressReport {
public:
  ProgressReport(const LoadOptions& options, std::filesystem::path file);
  /// `done` of `total` units of the current stage, mapped into [from, to] of the whole load.
  void stage(double from, double to) { mFrom = from; mTo = to; }
  void update(uint64_t done, uint64_t total);
  void finish() { report(1.0); }
  const LoadOptions& options() const { return mOptions; }

private:
  void report(double fraction);
  const LoadOptions& mOptions;
  std::filesystem::path mFile;
  double mFrom = 0.0, mTo = 1.0, mLast = 0.0;
};

/// Places a default sun (no lights) and a camera framing the bounds (when !hasCamera).
void addDefaultLightAndCamera(Scene& scene, bool hasCamera);

/// Appends `model`'s meshes, materials, images and objects to `scene`, placed by `worldFromModel`;
/// objects are named "<name>/<object>" and cast shadows only when `castsShadow`. Lights and the
/// camera of the model are not taken (the scene file has its own); its animated nodes are, placed
/// by `worldFromModel` (their lights' and camera's keys are not). Throws Error (naming
/// `where`) when the placed model breaks a limit.
void appendModel(Scene& scene, const Scene& model, const glm::mat4& worldFromModel, bool castsShadow,
                 const std::string& name, const std::string& where);

// --- helpers shared by the loaders --------------------------------------------------------------
/// "file: field: problem" (field may be empty).
[[noreturn]] void fail(const std::string& file, const std::string& field, const std::string& problem);

/// Reads a whole regular file of at most `maxBytes`. Throws Error naming `what` otherwise.
std::vector<uint8_t> readFileLimited(const std::filesystem::path& path, const std::string& what,
                                     uint64_t maxBytes = kMaxFileBytes);

/// What a scene's meshes will hold, counted before they are built.
struct SceneCounts {
  uint64_t vertices = 0, triangles = 0;
  uint64_t normals = 0, uvs = 0;  ///< vertices that keep a normal, a texture coordinate
  uint64_t loaderBytes = 0;       ///< what the loader holds besides the meshes while it builds them
};

/// The bytes a scene of `counts` takes, by part, as `options` will use it. Each part is the
/// measured cost per vertex and per triangle (docs/scenes.md#limits): the meshes (12 bytes a
/// position, 12 a normal, 8 a texture coordinate, 12 a triangle), the renderer's GL buffers (the
/// same, where they live in this process), the reference's BVH (its build's peak), and what the
/// loader holds on the way.
struct MemoryEstimate {
  uint64_t meshBytes = 0, glBytes = 0, bvhBytes = 0, loaderBytes = 0;
  /// The peak: while loading (the loader's own and the meshes), or once used (meshes, GL
  /// buffers, BVH), whichever is larger.
  uint64_t peakBytes() const;
};
MemoryEstimate estimateSceneMemory(const SceneCounts& counts, const LoadOptions& options);
/// BVH bytes per triangle of the reference's Embree scene at its build's peak: 94–102 measured on grids of
/// 0.5–8 M triangles (docs/bench.md#scale).
inline constexpr uint64_t kBvhBytesPerTriangle = 100;

/// Throws Error("file: N triangles, about M vertices: about X GiB (…), more than the Y GiB …")
/// when the estimate's peak exceeds options.maxMemoryBytes (0: the memory available).
void checkSceneMemory(const SceneCounts& counts, const std::string& file, const LoadOptions& options);

/// Checks the limits that only the whole scene shows: object, image totals,
/// finite world transforms and coordinates within kMaxCoordinateM. `file` names the error.
void checkSceneLimits(const Scene& scene, const std::string& file);

}  // namespace penumbra::loaders
