#pragma once
// Getting scenes: built-in names and scene files (JSON). Errors name the file and the field.
#include <penumbra/Scene.h>

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// Names of the built-in scenes, the default first.
std::vector<std::string> builtinSceneNames();
/// One-line description of a built-in scene.
std::string_view builtinSceneDescription(std::string_view name);
/// Builds a built-in scene; throws a usage Error for an unknown name.
Scene makeBuiltinScene(std::string_view name);

/// How a load reports on itself. Nothing is printed by the loaders; a tool shows what it likes.
struct LoadOptions {
  /// Called on the loading thread for each model file: with 0 when it starts, with increasing
  /// fractions while it is parsed and converted, with 1 when it is loaded. Empty: no reports.
  std::function<void(const std::filesystem::path& file, double fraction)> progress;
  /// Most memory (bytes) a model file may take once loaded and used as below; 0 = what this
  /// machine has available (MemAvailable, ulimit -v, the cgroup's limit). A model whose estimate
  /// is larger is refused, naming the estimate and the memory, before anything is built
  /// (docs/scenes.md#limits).
  uint64_t maxMemoryBytes = 0;
  /// What the caller makes of the scene besides its CPU copy, for the estimate: the renderer's
  /// vertex and index buffers in this process's memory (a software renderer such as llvmpipe
  /// keeps them there), …
  bool glBuffersInHostMemory = true;
  /// … and the reference's BVH (compare, bench, tune).
  bool referenceBvh = false;
  /// A model given alone (not placed by a scene file) whose meshes hold no floor under it gets a
  /// ground plane, so that its shadow has somewhere to fall (addGroundUnderModel). Off: as loaded.
  bool groundUnderLoneModel = false;
  /// Called with one sentence when the load adds what the file does not have (the ground, and
  /// why); a model that has a floor of its own is told apart too. Empty: no reports.
  std::function<void(const std::string& sentence)> notice = {};
};

/// The ground under a lone model: when no object is a floor (flat, at the bottom of the model's
/// bounds, under at least half its footprint), a grey square kGroundSpanFactor × the model's
/// larger horizontal side, centred under it at its lowest point, that receives shadows and casts
/// none. Returns the sentence saying what was done and why (a floor of its own: nothing added).
std::string addGroundUnderModel(Scene& scene);
/// The ground's side over the model's larger horizontal side: room for the long shadow of a low sun.
inline constexpr float kGroundSpanFactor = 4.0f;

/// Loads a scene JSON file. Throws Error("file: field: problem") on any bad input.
Scene loadSceneFile(const std::filesystem::path& path, const LoadOptions& options = {});

/// A built-in name, a scene file (.json) or a model file (.gltf, .glb, .obj).
Scene loadScene(const std::string& nameOrPath, const LoadOptions& options = {});

/// The --camera argument "X,Y,Z:TX,TY,TZ[:FOV]" (metres, vertical field of view in degrees) →
/// `base` with that position, target and, if given, field of view; up, near and far stay. Throws
/// a usage Error for anything else: a wrong count, a number that does not parse, is not finite or
/// lies beyond ±kMaxCoordinateM (1e6 m), the target on the position, a view along the up vector,
/// a field of view outside 1–170°.
Camera parseCameraArgument(const std::string& text, const Camera& base);

/// The camera as a --camera argument, exact enough to read back the same floats.
std::string cameraArgument(const Camera& camera);

}  // namespace penumbra
