// penumbra render: one frame of a scene with a technique, to PNG (+ visibility EXR, + dump); with
// --repeat, the last of several renders of the same frame (timing).
#include "Commands.h"
#include "Common.h"

#include "platform/Context.h"
#include "report/BenchResults.h"

#include <penumbra/Exr.h>
#include <penumbra/ImageIO.h>

#include <fmt/format.h>

#include <cstdio>
#include <memory>

namespace penumbra::app {

void addRenderCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    TechniqueOptions technique;
    std::string out = "penumbra.png";
    std::string visibility, dump;
    int frames = 1;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("render", "render one frame to a PNG (the default subcommand)");
  addTechniqueOptions(*sub, o->technique);
  addShadowBudgetOption(*sub, o->technique);
  sub->add_option("--out", o->out, "output PNG")->capture_default_str();
  sub->add_option("--visibility", o->visibility, "also write the visibility (1 = lit) as a float EXR");
  sub->add_option("--dump", o->dump, "write every intermediate (shadow maps, G-buffer, visibility) into this folder");
  sub->add_option("--repeat", o->frames,
                  "render the same frame this many times and write the last (the first compiles the shaders): for "
                  "timing; --verbose then prints each pass's median over the renders after the first")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  commands.push_back({sub, [o] {
    checkOutput("--out", o->out);
    if (!o->visibility.empty()) checkOutput("--visibility", o->visibility);
    if (!o->dump.empty()) checkOutputDir("--dump", o->dump);
    Setup s = makeSetup(o->technique);
    gl::HeadlessContext context({.debug = gl::kDebugBuild, .verbose = o->technique.verbose});
    checkImageFits(context, s.render.width, s.render.height,
                   kRenderHostBytesPerPixel + (o->visibility.empty() ? 0 : kVisibilityHostBytesPerPixel));
    const std::unique_ptr<Renderer> rendererPtr = makeRenderer(context, s);
    Renderer& renderer = *rendererPtr;
    renderer.render(s.render);
    std::vector<PassTimings> warm;  // the frames after the first
    for (int i = 1; i < o->frames; ++i) {
      renderer.render(s.render);
      warm.push_back(renderer.timings());
    }
    const ColorImage color = renderer.readColor();
    writePng(o->out, color.width, color.height, color.rgba);
    if (!o->visibility.empty()) {
      const std::vector<float> v = renderer.readVisibility();
      writeExr(o->visibility, s.render.width, s.render.height, flipRows<float>(v, s.render.width, s.render.height));
    }
    if (!o->dump.empty()) renderer.dump(o->dump);
    if (o->technique.verbose) {
      for (const auto& [pass, ms] : renderer.timings().ms) {
        std::vector<double> samples;
        for (const PassTimings& t : warm) samples.push_back(t.get(pass));
        std::fprintf(stderr, "penumbra: %-10s %8.2f ms\n", pass.c_str(), warm.empty() ? ms : report::timeStats(samples).median);
      }
      std::fprintf(stderr, "penumbra: times by %s on %s%s\n", renderer.timings().clock.c_str(), context.info().renderer.c_str(),
                   warm.empty() ? " (one frame: includes shader compilation)"
                                : fmt::format(" (medians of the {} frames after the first)", warm.size()).c_str());
    }
    std::printf("wrote %s (%dx%d, scene %s, --projection %s --filter %s)\n", o->out.c_str(), color.width, color.height,
                s.scene.name.c_str(), std::string(renderer.projection().id()).c_str(), std::string(renderer.filter().id()).c_str());
    return 0;
  }});
}

}  // namespace penumbra::app
