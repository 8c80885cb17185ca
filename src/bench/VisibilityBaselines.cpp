#include "bench/VisibilityBaselines.h"

#include "frame/SatBuilder.h"
#include "frame/ScreenTarget.h"
#include "gl/Objects.h"
#include "micro/lookup.shared.h"
#include "bench/MicroBenchmarks.h"
#include "core/ShadowsAccess.h"
#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>
#include "techniques/Registry.h"
#include <penumbra/Renderer.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_access.hpp>

#include <cmath>
#include <functional>
#include <memory>

namespace penumbra::report {
namespace {

// A kernel must find the shadow its pass finds, up to what it leaves out (the bias geometry, the
// filter's exact kernel or footprint, N·L): shadowOverlap measured 0.71–0.94 on boxes from 96×64
// to 1280×720. A kernel with acne (a bias of 2·10⁻⁴ without the slope term) scored below 0.05; one
// that reads the wrong map, view or matrix, or returns 1, near 0.
constexpr double kMinShadowOverlap = 0.5;

// What a kernel's constants are made from: the filter's own parameters and the view's texel.
struct KernelInputs {
  const Parameterized& filter;  // the pass's filter's values
  float texelDepth;  // one texel's world size as linear light depth (texelDepthVariance's unit)
  int mapSize;
};

// A kernel of one filter's lookup.
struct KernelDesc {
  const char* name;
  const char* text;  // what the kernel does, for the table
  int kind;          // PN_LOOKUP_*
  std::function<glm::vec4(const KernelInputs&)> params4;  // LookupUniforms::params
  bool footprint = false;  // LOOKUP_FOOTPRINT
};

// One filter's visibility pass and the kernels of its lookup: the first is the minimal one (the
// filter's arithmetic at its simplest: one tap, a plain box); a second, where the filter's own
// pattern or footprint is more work than that, does the same taps as the pass, so that the pass's
// overhead beyond its taps is a ratio of its own (its row: passName + kSameTapsSuffix).
struct Pairing {
  const char* filter;  // registry id
  std::vector<std::pair<std::string, std::string>> params;  // over the filter's defaults
  const char* passName;
  bool hardwareCompare;
  std::string_view mapImage;  // the Filter::debugImages() entry that holds the map the kernel reads
  std::vector<KernelDesc> kernels;
  // No kernels of its own: the pass (the filter with other parameters) is measured against this
  // kernel of an earlier pairing, timed in the same rounds.
  const char* sharedKernel = nullptr;
};
constexpr const char* kSameTapsSuffix = ", against the kernel of its own taps";

// The kernels have one constant depth bias where the filters slope-scale theirs per pixel (that
// needs the normal: bias geometry, the overhead being measured). Without a slope term a constant
// bias of 2·10⁻⁴ leaves acne on half of boxes' floor (30° from the sun); the filter's slope bias
// taken at this tangent (63°) covers it and every receiver up to that slope.
constexpr float kKernelSlopeTangent = 2.0f;
float kernelBias(const KernelInputs& in, const char* filter) {
  return in.filter.param(fmt::format("{}.constantBias", filter)) +
         in.filter.param(fmt::format("{}.slopeBias", filter)) * in.texelDepth * kKernelSlopeTangent;
}

float log2Texels(float texels) { return std::log2(std::max(texels, 1.0f)); }

// A variance stated in texels² (the filters' variance floors and moment biases) in linear depth²,
// as common/shadow.glsl's texelDepthVariance.
float texelsSquaredToDepth(const KernelInputs& in, float texelsSquared) { return texelsSquared * in.texelDepth * in.texelDepth; }

// pcf's default is 16 Poisson taps: the box with as many taps is 4 × 4.
int boxSide(const Parameterized& pcf) { return std::max(1, static_cast<int>(std::lround(std::sqrt(pcf.param("pcf.samples"))))); }

// A 4 × 4 box spanning pcf's ±radius: the taps are 2·radius / 3 texels apart. pcf follows the
// receiver's plane to every tap; the kernel's one bias grows by the slope across the radius instead.
glm::vec4 pcfParams(const KernelInputs& in) {
  const int side = boxSide(in.filter);
  const float radiusTexels = in.filter.param("pcf.radiusTexels");
  const float spacingTexels = side > 1 ? 2.0f * radiusTexels / static_cast<float>(side - 1) : 0.0f;
  return {kernelBias(in, "pcf") + radiusTexels * in.texelDepth * kKernelSlopeTangent, spacingTexels / static_cast<float>(in.mapSize), 0.0f, 0.0f};
}

// pcf's Poisson disk as the kernel reads it: its radius in uv, the bias grown over that radius.
glm::vec4 poissonParams(const KernelInputs& in) {
  const float radiusTexels = in.filter.param("pcf.radiusTexels");
  return {kernelBias(in, "pcf") + radiusTexels * in.texelDepth * kKernelSlopeTangent, radiusTexels / static_cast<float>(in.mapSize), 0.0f, 0.0f};
}

// The moments' kernels (vsm: 2, msm: 4): one trilinear tap at the filter's width, or the pixel's
// footprint widened to it; the variance floor or moment bias from `floorKey`.
glm::vec4 momentParams(const KernelInputs& in, const char* filter, const char* floorKey) {
  const float widthTexels = in.filter.param(fmt::format("{}.filterTexels", filter));
  return {0.0f, widthTexels, log2Texels(widthTexels), texelsSquaredToDepth(in, in.filter.param(floorKey))};
}
glm::vec4 vsmParams(const KernelInputs& in) { return momentParams(in, "vsm", "vsm.minVariance"); }
glm::vec4 msmParams(const KernelInputs& in) { return momentParams(in, "msm", "msm.bias"); }

const std::vector<Pairing>& pairings() {
  static const std::vector<Pairing> list = {
      {"hard", {}, "visibility: hard", false, kShadowMapImage,
       {{"lookup: one fetch and compare", "one texelFetch of the depth map and a compare with one constant bias", PN_LOOKUP_COMPARE,
         [](const KernelInputs& in) { return glm::vec4(kernelBias(in, "hard"), 0.0f, 0.0f, 0.0f); }}}},
      {"pcf", {}, "visibility: pcf", false, kShadowMapImage,
       {{"lookup: box of fetch-and-compares",
         "a box of texelFetch-and-compares with as many taps as pcf's default (16 Poisson taps: 4x4) over its radius",
         PN_LOOKUP_BOX, pcfParams},
        {"lookup: turned Poisson disk of fetch-and-compares",
         "pcf's own taps: its 16 Poisson points over its radius, turned per pixel as pcf turns them, each a "
         "texelFetch-and-compare with one constant bias",
         PN_LOOKUP_POISSON, poissonParams}}},
      {"pcf", {{"pcf.hardwareCompare", "on"}}, "visibility: pcf, hardwareCompare=on", true, kShadowMapImage,
       {{"lookup: box of hardware 2x2 compares", "the same box, each tap the hardware's bilinear 2x2 comparison (sampler2DArrayShadow)",
         PN_LOOKUP_BOX, pcfParams}}},
      {"vsm", {}, "visibility: vsm", false, kMomentsImage,
       {{"lookup: one trilinear (z, z²) tap + Chebyshev",
         "one trilinear textureLod of the moments' mip chain at vsm's filter width, Chebyshev's bound over its variance floor",
         PN_LOOKUP_MOMENTS2, vsmParams},
        {"lookup: one pixel footprint of (z, z²) + Chebyshev",
         "vsm's own taps: the pixel's footprint (ray differentials on the tangent plane, widened to vsm's filter "
         "width) read as up to vsm.anisotropy trilinear taps along its long axis (common/footprint.glsl), "
         "Chebyshev's bound over its variance floor",
         PN_LOOKUP_MOMENTS2, vsmParams, true}}},
      {"vssm", {}, "visibility: vssm", false, kShadowMapImage,
       {{"lookup: one SAT box mean + Chebyshev",
         "one exact box mean of the (z, z²) summed-area table (16 corner reads, vssm's filter step at its minimum radius), "
         "Chebyshev's bound over its variance floor",
         PN_LOOKUP_SAT, [](const KernelInputs& in) {
           return glm::vec4(0.0f, 0.0f, in.filter.param("vssm.minRadiusTexels"),
                            texelsSquaredToDepth(in, in.filter.param("vssm.minVariance")));
         }}}},
      {"smrt", {}, "visibility: smrt", false, kShadowMapImage,
       {{"lookup: rays marched through the map",
         "smrt's taps on every pixel: as many rays toward the sun's disk as smrt's smrt.rays (its sunflower, turned per "
         "pixel), each smrt.steps fetch-and-compares from the receiver to the near plane, with one constant bias; no "
         "probe, no nearest-caster search, no thickness or crossing test",
         PN_LOOKUP_MARCH, [](const KernelInputs& in) { return glm::vec4(kernelBias(in, "smrt"), 0.0f, 0.0f, 0.0f); }}}},
      {"msm", {}, "visibility: msm", false, kMomentsImage,
       {{"lookup: one trilinear 4-moment tap + Hamburger 4MSM",
         "one trilinear textureLod of the four moments' mip chain at msm's filter width, the moment bias, the Hamburger 4MSM bound",
         PN_LOOKUP_MOMENTS4, msmParams},
        {"lookup: one pixel footprint of 4 moments + Hamburger 4MSM",
         "msm's own taps: the pixel's footprint read as vsm's (up to msm.anisotropy trilinear taps), the moment bias, "
         "the Hamburger 4MSM bound",
         PN_LOOKUP_MOMENTS4, msmParams, true}}},
      // The moment filters without the footprint read one trilinear tap of the filter's width: the
      // one-tap kernel's own work, so their ratio is the filters' overhead beyond their arithmetic
      // (the defaults' extra is the footprint's anisotropic taps, up to {vsm,msm}.anisotropy).
      {"vsm", {{"vsm.footprint", "off"}}, "visibility: vsm, footprint=off", false, kMomentsImage, {},
       "lookup: one trilinear (z, z²) tap + Chebyshev"},
      {"msm", {{"msm.footprint", "off"}}, "visibility: msm, footprint=off", false, kMomentsImage, {},
       "lookup: one trilinear 4-moment tap + Hamburger 4MSM"},
  };
  return list;
}

// The renderer of one pairing's filter (one per pairing, so that nothing is rebuilt between
// rounds), the G-buffer's positions and geometric normals copied out of it, and the kernel's own
// output.
struct PassFixture {
  Renderer renderer;
  RenderOptions options;
  gl::Texture position, geoNormal, visibility;
  ScreenTarget visibilityTarget;  // the kernels draw into `visibility`, as the pass into its layer

  PassFixture(const VisibilityBaselineSettings& s, const Pairing& p)
      : options{.width = s.width, .height = s.height, .debugView = 0} {
    Scene scene = makeBuiltinScene(s.scene);
    Technique technique("uniform", p.filter);
    technique.setMapSize(s.mapSize);
    applySettings(p.params, scene, technique);
    renderer.setScene(scene);
    renderer.setTechnique(technique);
    renderer.render(options);
    const GBufferData g = renderer.readGBuffer();
    position = gBufferTexture("lookup kernel positions", s, g.position);
    geoNormal = gBufferTexture("lookup kernel geometric normals", s, g.geoNormal);
    visibility = gl::Texture("lookup kernel visibility", {GL_TEXTURE_2D, GL_R32F, s.width, s.height, 1, 1});
    visibilityTarget = ScreenTarget("lookup kernel", visibility);
  }

  static gl::Texture gBufferTexture(const char* label, const VisibilityBaselineSettings& s, const std::vector<glm::vec4>& texels) {
    gl::Texture t(label, {GL_TEXTURE_2D, GL_RGBA32F, s.width, s.height, 1, 1});
    t.setSampling(GL_NEAREST, GL_NEAREST);
    glTextureSubImage2D(t.id(), 0, 0, 0, s.width, s.height, GL_RGBA, GL_FLOAT, texels.data());
    return t;
  }

  const gl::Texture& map(std::string_view name) {
    for (const DebugImage& d : debugImages(renderer.shadows()))
      if (d.name == name && d.texture) return *d.texture;
    throw Error(fmt::format("lookup kernel: the filter has no image '{}'", name));
  }
};

using SharedFixture = std::shared_ptr<std::shared_ptr<PassFixture>>;

// The one matrix of the kernel: the view's clipFromWorld taken to map uv (rows 0, 1 and 3), its
// depth plane as row 2.
glm::mat4 mapFromWorld(const ShadowView& v) {
  const glm::mat4& m = v.clipFromWorld;
  const glm::vec4 rowW = glm::row(m, 3);
  return glm::transpose(glm::mat4(0.5f * (glm::row(m, 0) + rowW), 0.5f * (glm::row(m, 1) + rowW), v.depthPlane, rowW));
}

// One texel's world size as linear depth: orthographic views everywhere, perspective ones at the
// middle of their depth range (the kernel has one constant where the filters have a per-pixel size).
float texelDepth(const ShadowView& v, int mapSize) {
  const float distance = v.perspective ? 0.5f * (v.nearM + v.farM) : 1.0f;
  const float texelM = std::max(v.extent.x, v.extent.y) * distance / static_cast<float>(mapSize);
  return texelM / (v.farM - v.nearM);
}

// How well a kernel's shadow matches its pass's: the intersection over the union of the pixels
// each calls shadowed (V < 0.5). A kernel that returned 1 everywhere, read the wrong map or view
// scores near 0; acne adds to the union. 1 where neither has a shadow.
double shadowOverlap(const std::vector<float>& kernel, const std::vector<float>& pass) {
  constexpr float kShadowed = 0.5f;
  size_t both = 0, either = 0;
  for (size_t i = 0; i < kernel.size(); ++i) {
    const bool k = kernel[i] < kShadowed, p = pass[i] < kShadowed;
    both += k && p;
    either += k || p;
  }
  return either > 0 ? static_cast<double>(both) / static_cast<double>(either) : 1.0;
}

// The camera's part of the kernel's block: what the footprint's ray differentials need.
void setCamera(gpu::LookupUniforms& u, const Camera& camera, int width, int height) {
  const glm::mat4 viewFromWorld = camera.viewFromWorld();
  const glm::mat4 clipFromView = camera.clipFromView(static_cast<float>(width) / static_cast<float>(height));
  // A ray's direction at unit view depth is V⁻¹(ndc.x / P00, ndc.y / P11, −1); one pixel is 2 / size of ndc.
  u.cameraPosition = glm::vec4(camera.position, 1.0f);
  u.cameraForward = glm::vec4(-glm::vec3(glm::row(viewFromWorld, 2)), 0.0f);
  u.rayStepX = glm::vec4(glm::vec3(glm::row(viewFromWorld, 0)) * (2.0f / (static_cast<float>(width) * clipFromView[0][0])), 0.0f);
  u.rayStepY = glm::vec4(glm::vec3(glm::row(viewFromWorld, 1)) * (2.0f / (static_cast<float>(height) * clipFromView[1][1])), 0.0f);
}

// The kernel's program, inputs and dispatch, bound to one fixture.
struct Kernel {
  std::shared_ptr<PassFixture> fixture;
  ShaderLibrary shaders;
  gl::Buffer block{"lookup kernel block", sizeof(gpu::LookupUniforms)};
  gl::Sampler sampler;
  SatBuilder sat;
  const gl::Texture* map = nullptr;
  const gl::Program* program = nullptr;
  int kind = 0;
  bool footprint = false;

  Kernel(std::shared_ptr<PassFixture> f, const Pairing& p, const KernelDesc& k, int mapSize)
      : fixture(std::move(f)), kind(k.kind), footprint(k.footprint) {
    const Parameterized& filter = fixture->renderer.technique().filterValues();
    ProgramDesc d;
    d.label = k.name;
    d.fragment = {"micro/lookup.glsl"};
    d.defines.set("LOOKUP_KIND", k.kind);
    if (k.kind == PN_LOOKUP_BOX || k.kind == PN_LOOKUP_POISSON) d.defines.set("LOOKUP_SIDE", boxSide(filter));
    if (k.footprint) d.defines.set("LOOKUP_FOOTPRINT");
    if (k.kind == PN_LOOKUP_MARCH) {
      d.defines.set("LOOKUP_RAYS", filter.paramInt("smrt.rays"));
      d.defines.set("LOOKUP_STEPS", filter.paramInt("smrt.steps"));
    }
    if (p.hardwareCompare) d.defines.set("PN_HARDWARE_COMPARE");
    program = &shaders.program(fullScreenProgram(d));  // drawn, as the visibility pass is
    map = &fixture->map(p.mapImage);
    if (k.kind == PN_LOOKUP_SAT) sat.build(shaders, *map, 2);
    if (p.hardwareCompare) {
      gl::SamplerDesc compare;
      compare.compare = true;  // bilinear, clamp to edge: as pcf's ComparisonSampler
      sampler = gl::Sampler("lookup kernel comparison", compare);
    } else if (k.kind == PN_LOOKUP_MOMENTS2 || k.kind == PN_LOOKUP_MOMENTS4) {
      gl::SamplerDesc trilinear;
      trilinear.minFilter = GL_LINEAR_MIPMAP_LINEAR;
      sampler = gl::Sampler("lookup kernel trilinear", trilinear);
    }
    const ShadowView& view = fixture->renderer.frusta().views.front();
    gpu::LookupUniforms u{};
    u.mapFromWorld = mapFromWorld(view);
    u.params = k.params4({filter, texelDepth(view, mapSize), mapSize});
    const int maxTaps = k.footprint ? filter.paramInt(fmt::format("{}.anisotropy", p.filter)) : 0;
    u.mapSize = glm::ivec4(map->width(), map->height(), maxTaps, 0);
    setCamera(u, fixture->renderer.scene().camera, fixture->position.width(), fixture->position.height());
    if (k.kind == PN_LOOKUP_MARCH) {
      const Light& sun = fixture->renderer.scene().light();
      PN_CHECK(sun.type == LightType::Directional, fmt::format("{}: the march kernel follows a sun", k.name));
      u.light = glm::vec4(-sun.direction, std::tan(sun.size));
    }
    block.upload(u);
  }

  void run() const {
    block.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FILTER);
    fixture->position.bindUnit(PN_TEX_GBUF_POSITION);
    if (footprint) fixture->geoNormal.bindUnit(PN_TEX_GBUF_GEONORMAL);
    if (kind == PN_LOOKUP_SAT) {
      sat.bindTable();
    } else {
      map->bindUnit(PN_TEX_FILTER0);
      if (sampler) sampler.bindUnit(PN_TEX_FILTER0);
    }
    fixture->visibilityTarget.draw(*program, {fixture->position.width(), fixture->position.height()});
    glBindSampler(PN_TEX_FILTER0, 0);  // the renderer's passes use this unit with their own state
  }
};

std::shared_ptr<PassFixture> fixtureOf(const SharedFixture& shared, const VisibilityBaselineSettings& s, const Pairing& p) {
  if (!*shared) *shared = std::make_shared<PassFixture>(s, p);
  return *shared;
}

}  // namespace

std::vector<MicroResult> runVisibilityBaselines(const VisibilityBaselineSettings& s) {
  const std::string where = fmt::format("{} at {}x{}, a {}² map, the uniform projection", s.scene, s.width, s.height, s.mapSize);
  std::vector<MicroItem> items;
  for (const Pairing& p : pairings()) {
    const SharedFixture shared = std::make_shared<std::shared_ptr<PassFixture>>();
    auto kernelItem = [&](const KernelDesc& k) {
      return MicroItem{k.name, fmt::format("{} ({}; micro/lookup.glsl)", k.text, where), "", [shared, s, &p, &k] {
                         auto kernel = std::make_shared<Kernel>(fixtureOf(shared, s, p), p, k, s.mapSize);
                         // It must compute what its pass computes before it stands for the pass's arithmetic.
                         kernel->run();
                         std::vector<float> v(static_cast<size_t>(s.width) * static_cast<size_t>(s.height));
                         kernel->fixture->visibility.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
                         const double overlap = shadowOverlap(v, kernel->fixture->renderer.readVisibility());
                         PN_CHECK(overlap >= kMinShadowOverlap,
                                  fmt::format("the kernel's shadow overlaps {}'s by {:.2f} (intersection over union; at "
                                              "least {} expected): it does not do the same lookup",
                                              p.passName, overlap, kMinShadowOverlap));
                         return timedWork(s.cpuClock, k.name, [kernel] { kernel->run(); });
                       }};
    };
    std::string params;
    for (const auto& [k, v] : p.params) params += fmt::format(", {}={}", k, v);
    const std::string passText =
        fmt::format("the visibility pass of {} (its defaults{}) in a frame of penumbra::Renderer ({})", p.filter, params, where);
    if (!p.sharedKernel) items.push_back(kernelItem(p.kernels.front()));
    items.push_back({p.passName, passText, p.sharedKernel ? p.sharedKernel : p.kernels.front().name, [shared, s, &p] {
                       auto f = fixtureOf(shared, s, p);
                       return std::function<double()>([f] {
                         f->renderer.render(f->options);
                         return f->renderer.timings().get("visibility");
                       });
                     }});
    for (size_t k = 1; k < p.kernels.size(); ++k) {
      items.push_back(kernelItem(p.kernels[k]));
      items.push_back({std::string(p.passName) + kSameTapsSuffix, passText, p.kernels[k].name, {}, p.passName});
    }
  }
  return runMicroItems(items, s.rounds);
}

}  // namespace penumbra::report
