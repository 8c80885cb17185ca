#include "report/VisibilityBaselines.h"

#include "frame/FrameContext.h"
#include "frame/SatBuilder.h"
#include "gl/Objects.h"
#include "micro/lookup.shared.h"
#include "report/MicroBenchmarks.h"
#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>
#include <penumbra/Registry.h>
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
  const Filter& filter;
  float texelDepth;  // one texel's world size as linear light depth (texelDepthVariance's unit)
  int mapSize;
};

// One filter's visibility pass and the kernel of the same lookup.
struct Pairing {
  const char* filter;  // registry id
  std::vector<std::pair<std::string, std::string>> params;  // over the filter's defaults
  const char* passName;
  const char* kernelName;
  const char* kernelText;  // what the kernel does, for the table
  int kind;                // PN_LOOKUP_*
  bool hardwareCompare;
  std::string_view mapImage;  // the Filter::debugImages() entry that holds the map the kernel reads
  std::function<glm::vec4(const KernelInputs&)> params4;  // LookupUniforms::params
};

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
int boxSide(const Filter& pcf) { return std::max(1, static_cast<int>(std::lround(std::sqrt(pcf.param("pcf.samples"))))); }

// A 4 × 4 box spanning pcf's ±radius: the taps are 2·radius / 3 texels apart. pcf follows the
// receiver's plane to every tap; the kernel's one bias grows by the slope across the radius instead.
glm::vec4 pcfParams(const KernelInputs& in) {
  const int side = boxSide(in.filter);
  const float radiusTexels = in.filter.param("pcf.radiusTexels");
  const float spacingTexels = side > 1 ? 2.0f * radiusTexels / static_cast<float>(side - 1) : 0.0f;
  return {kernelBias(in, "pcf") + radiusTexels * in.texelDepth * kKernelSlopeTangent, spacingTexels / static_cast<float>(in.mapSize), 0.0f, 0.0f};
}

const std::vector<Pairing>& pairings() {
  static const std::vector<Pairing> list = {
      {"hard", {}, "visibility: hard", "lookup: one fetch and compare",
       "one texelFetch of the depth map and a compare with one constant bias", PN_LOOKUP_COMPARE, false, kShadowMapImage,
       [](const KernelInputs& in) { return glm::vec4(kernelBias(in, "hard"), 0.0f, 0.0f, 0.0f); }},
      {"pcf", {}, "visibility: pcf", "lookup: box of fetch-and-compares",
       "a box of texelFetch-and-compares with as many taps as pcf's default (16 Poisson taps: 4x4) over its radius",
       PN_LOOKUP_BOX, false, kShadowMapImage, pcfParams},
      {"pcf", {{"pcf.hardwareCompare", "on"}}, "visibility: pcf, hardwareCompare=on", "lookup: box of hardware 2x2 compares",
       "the same box, each tap the hardware's bilinear 2x2 comparison (sampler2DArrayShadow)", PN_LOOKUP_BOX, true,
       kShadowMapImage, pcfParams},
      {"vsm", {}, "visibility: vsm", "lookup: one trilinear (z, z²) tap + Chebyshev",
       "one trilinear textureLod of the moments' mip chain at vsm's filter width, Chebyshev's bound over its variance floor",
       PN_LOOKUP_MOMENTS2, false, kMomentsImage,
       [](const KernelInputs& in) {
         return glm::vec4(0.0f, 0.0f, log2Texels(in.filter.param("vsm.filterTexels")),
                          texelsSquaredToDepth(in, in.filter.param("vsm.minVariance")));
       }},
      {"vssm", {}, "visibility: vssm", "lookup: one SAT box mean + Chebyshev",
       "one exact box mean of the (z, z²) summed-area table (16 corner reads, vssm's filter step at its minimum radius), "
       "Chebyshev's bound over its variance floor",
       PN_LOOKUP_SAT, false, kShadowMapImage,
       [](const KernelInputs& in) {
         return glm::vec4(0.0f, 0.0f, in.filter.param("vssm.minRadiusTexels"),
                          texelsSquaredToDepth(in, in.filter.param("vssm.minVariance")));
       }},
      {"msm", {}, "visibility: msm", "lookup: one trilinear 4-moment tap + Hamburger 4MSM",
       "one trilinear textureLod of the four moments' mip chain at msm's filter width, the moment bias, the Hamburger 4MSM bound",
       PN_LOOKUP_MOMENTS4, false, kMomentsImage,
       [](const KernelInputs& in) {
         return glm::vec4(0.0f, 0.0f, log2Texels(in.filter.param("msm.filterTexels")),
                          texelsSquaredToDepth(in, in.filter.param("msm.bias")));
       }},
  };
  return list;
}

// The renderer of one pairing's filter (one per pairing, so that nothing is rebuilt between
// rounds), the G-buffer's positions copied out of it, and the kernel's own output.
struct PassFixture {
  Renderer renderer;
  RenderOptions options;
  gl::Texture position, visibility;

  PassFixture(const VisibilityBaselineSettings& s, const Pairing& p)
      : options{.width = s.width, .height = s.height, .shadowMapSize = s.mapSize, .debugView = 0} {
    Scene scene = makeBuiltinScene(s.scene);
    std::unique_ptr<Projection> projection = makeProjection("uniform");
    std::unique_ptr<Filter> filter = makeFilter(p.filter);
    applyParams(p.params, scene, *projection, *filter);
    renderer.setScene(scene);
    renderer.setTechnique(std::move(projection), std::move(filter));
    renderer.render(options);
    const GBufferData g = renderer.readGBuffer();
    position = gl::Texture("lookup kernel positions", {GL_TEXTURE_2D, GL_RGBA32F, s.width, s.height, 1, 1});
    position.setSampling(GL_NEAREST, GL_NEAREST);
    glTextureSubImage2D(position.id(), 0, 0, 0, s.width, s.height, GL_RGBA, GL_FLOAT, g.position.data());
    visibility = gl::Texture("lookup kernel visibility", {GL_TEXTURE_2D, GL_R32F, s.width, s.height, 1, 1});
  }

  const gl::Texture& map(std::string_view name) {
    for (const DebugImage& d : renderer.filter().debugImages())
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

  Kernel(std::shared_ptr<PassFixture> f, const Pairing& p, int mapSize) : fixture(std::move(f)), kind(p.kind) {
    ProgramDesc d;
    d.label = p.kernelName;
    d.compute = {"micro/lookup.comp.glsl"};
    d.defines.set("LOOKUP_KIND", p.kind);
    if (p.kind == PN_LOOKUP_BOX) d.defines.set("LOOKUP_SIDE", boxSide(fixture->renderer.filter()));
    if (p.hardwareCompare) d.defines.set("PN_HARDWARE_COMPARE");
    program = &shaders.program(d);
    map = &fixture->map(p.mapImage);
    if (p.kind == PN_LOOKUP_SAT) sat.build(shaders, *map, 2);
    if (p.hardwareCompare) {
      gl::SamplerDesc compare;
      compare.compare = true;  // bilinear, clamp to edge: as pcf's ComparisonSampler
      sampler = gl::Sampler("lookup kernel comparison", compare);
    } else if (p.kind == PN_LOOKUP_MOMENTS2 || p.kind == PN_LOOKUP_MOMENTS4) {
      gl::SamplerDesc trilinear;
      trilinear.minFilter = GL_LINEAR_MIPMAP_LINEAR;
      sampler = gl::Sampler("lookup kernel trilinear", trilinear);
    }
    const ShadowView& view = fixture->renderer.frusta().views.front();
    gpu::LookupUniforms u{};
    u.mapFromWorld = mapFromWorld(view);
    u.params = p.params4({fixture->renderer.filter(), texelDepth(view, mapSize), mapSize});
    u.mapSize = glm::ivec4(map->width(), map->height(), 0, 0);
    block.upload(u);
  }

  void run() const {
    block.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FILTER);
    fixture->position.bindUnit(PN_TEX_GBUF_POSITION);
    fixture->visibility.bindImage(PN_IMG_VISIBILITY, GL_WRITE_ONLY);
    if (kind == PN_LOOKUP_SAT) {
      sat.bindTable();
    } else {
      map->bindUnit(PN_TEX_FILTER0);
      if (sampler) sampler.bindUnit(PN_TEX_FILTER0);
    }
    FrameContext::dispatch2D(*program, fixture->position.width(), fixture->position.height(), PN_SCREEN_GROUP);
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
    items.push_back({p.kernelName, fmt::format("{} ({}; micro/lookup.comp.glsl)", p.kernelText, where), "", [shared, s, &p] {
                       auto kernel = std::make_shared<Kernel>(fixtureOf(shared, s, p), p, s.mapSize);
                       // It must compute what its pass computes before it stands for the pass's arithmetic.
                       kernel->run();
                       std::vector<float> v(static_cast<size_t>(s.width) * static_cast<size_t>(s.height));
                       kernel->fixture->visibility.read(GL_RED, GL_FLOAT, v.data(), v.size() * sizeof(float));
                       const double overlap = shadowOverlap(v, kernel->fixture->renderer.readVisibility());
                       PN_CHECK(overlap >= kMinShadowOverlap,
                                fmt::format("the kernel's shadow overlaps {}'s by {:.2f} (intersection over union; at "
                                            "least {} expected): it does not do the same lookup",
                                            p.passName, overlap, kMinShadowOverlap));
                       return timedWork(s.cpuClock, p.kernelName, [kernel] { kernel->run(); });
                     }});
    std::string params;
    for (const auto& [k, v] : p.params) params += fmt::format(", {}={}", k, v);
    items.push_back({p.passName,
                     fmt::format("the visibility pass of {} (its defaults{}) in a frame of penumbra::Renderer ({})", p.filter, params, where),
                     p.kernelName, [shared, s, &p] {
                       auto f = fixtureOf(shared, s, p);
                       return std::function<double()>([f] {
                         f->renderer.render(f->options);
                         return f->renderer.timings().get("visibility");
                       });
                     }});
  }
  return runMicroItems(items, s.rounds);
}

}  // namespace penumbra::report
