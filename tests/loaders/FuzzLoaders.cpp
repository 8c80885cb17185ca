// libFuzzer target for the scene-file, glTF and OBJ loaders (built by clang++ only;
// tests/loaders/CMakeLists.txt). PENUMBRA_FUZZ_TARGET selects what one input is:
//   gltf  - the bytes of a .gltf or .glb file (external URIs resolve against the seed folder);
//           the seeds reach every decoder: PNG and JPEG textures, Draco and meshopt geometry;
//   obj   - the text of an .obj file (its mtllib resolves against the seed folder);
//   scene - the text of a scene file, written to a scratch folder next to a link to
//           tests/data/models so that its "file" objects reach real glTF and OBJ models.
// A penumbra::Error is the expected answer to bad input; anything else that escapes (another
// exception, a sanitizer report, a timeout, memory beyond -rss_limit_mb) is a bug.
#include "base/StbImageFormats.h"
#define STB_IMAGE_IMPLEMENTATION  // penumbra_base has it in base/ImageIO.cpp, which this build leaves out
#include <stb_image.h>

#include "sceneio/loaders/GltfLoader.h"
#include "sceneio/loaders/ModelImport.h"
#include "sceneio/loaders/ObjLoader.h"

#include <penumbra/Error.h>
#include <penumbra/SceneIO.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

enum class Target { Gltf, Obj, Scene };
Target gTarget = Target::Gltf;
fs::path gScratch;

void removeScratch() {
  std::error_code ec;
  if (!gScratch.empty()) fs::remove_all(gScratch, ec);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* target = std::getenv("PENUMBRA_FUZZ_TARGET");
  const std::string t = target ? target : "gltf";
  if (t == "scene") gTarget = Target::Scene;
  else if (t == "obj") gTarget = Target::Obj;
  else if (t != "gltf") {
    std::fprintf(stderr, "PENUMBRA_FUZZ_TARGET=%s: expected gltf, obj or scene\n", t.c_str());
    std::exit(2);
  }
  if (gTarget == Target::Scene) {
    gScratch = fs::temp_directory_path() / ("penumbra-fuzz-" + std::to_string(getpid()));
    fs::create_directories(gScratch);
    fs::create_symlink(fs::path(PENUMBRA_TEST_DATA) / "models", gScratch / "models");
    std::atexit(removeScratch);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    if (gTarget == Target::Gltf) {
      penumbra::loaders::Model m = penumbra::loaders::loadGltfFromMemory(
          {data, size}, "fuzz.gltf", fs::path(PENUMBRA_TEST_DATA) / "fuzz" / "gltf");
      penumbra::loaders::checkSceneLimits(m.scene, "fuzz.gltf");
      penumbra::loaders::addDefaultLightAndCamera(m.scene, m.hasCamera);
      m.scene.validate();
    } else if (gTarget == Target::Obj) {
      penumbra::loaders::Model m = penumbra::loaders::loadObjFromMemory(std::string(reinterpret_cast<const char*>(data), size),
                                                                        "fuzz.obj", fs::path(PENUMBRA_TEST_DATA) / "fuzz" / "obj");
      penumbra::loaders::checkSceneLimits(m.scene, "fuzz.obj");
      penumbra::loaders::addDefaultLightAndCamera(m.scene, m.hasCamera);
      m.scene.validate();
    } else {
      const fs::path file = gScratch / "scene.json";
      std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
      penumbra::loadScene(file.string()).validate();
    }
  } catch (const penumbra::Error&) {
    // the expected answer to bad input
  }
  return 0;
}
