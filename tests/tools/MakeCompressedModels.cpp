// Writes the compressed glTF test data (tests/support/CompressedModels.h) into tests/data/:
//   models/draco_box.glb, models/meshopt_box.glb   rendered by the sanitizer build, fuzz seeds
//   fuzz/gltf/draco_box.glb, fuzz/gltf/meshopt_box.glb
//   bad/draco_*.glb, bad/meshopt_*.glb              each refused with one message
// Usage: penumbra_make_compressed_models tests/data   (rerun after changing CompressedModels.cpp)
#include "CompressedModels.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

void write(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
  std::printf("wrote %s (%zu bytes)\n", path.string().c_str(), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s TESTS_DATA_FOLDER\n", argv[0]);
    return 2;
  }
  const std::filesystem::path data = argv[1];
  try {
    for (const char* folder : {"models", "fuzz/gltf"}) {
      write(data / folder / "draco_box.glb", penumbra::test::dracoBoxGlb());
      write(data / folder / "meshopt_box.glb", penumbra::test::meshoptBoxGlb());
    }
    for (const auto& [name, bytes] : penumbra::test::brokenCompressedFiles()) write(data / "bad" / name, bytes);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
