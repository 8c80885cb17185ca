// penumbra render: one frame of a scene with a technique, to PNG (+ visibility EXR, + dump); with
// --repeat, the last of several renders of the same frame (timing); with --frames, a numbered PNG
// sequence of an animated scene (and an MP4 through ffmpeg when it is on the PATH).
#include "Commands.h"
#include "Common.h"

#include "base/AtomicFile.h"
#include "platform/Context.h"
#include "bench/BenchResults.h"

#include <penumbra/Exr.h>
#include <penumbra/ImageIO.h>

#include <fmt/format.h>

#include <penumbra/Animation.h>
#include <penumbra/Error.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

namespace penumbra::app {
namespace {

/// The ffmpeg executable on the PATH, or nothing.
std::optional<std::filesystem::path> findFfmpeg() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    std::error_code ec;
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / "ffmpeg";
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  }
  return std::nullopt;
}

/// A command line for messages: the words, those with a space or a quote single-quoted (as a
/// shell would read them back).
std::string displayed(const std::vector<std::string>& argv) {
  std::string out;
  for (const std::string& a : argv) {
    if (!out.empty()) out += ' ';
    if (!a.empty() && a.find_first_of(" '\"\\$`") == std::string::npos) {
      out += a;
      continue;
    }
    out += '\'';
    for (char c : a) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

/// Runs the program argv[0] with the arguments argv[1..] (no shell: nothing in them is
/// interpreted) and waits for it. Returns "" when it exits 0, else what happened.
std::string runProgram(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (const int e = posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ); e != 0)
    return fmt::format("cannot start it ({})", std::strerror(e));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return fmt::format("cannot wait for it ({})", std::strerror(errno));
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 0 ? "" : fmt::format("it exited with status {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return fmt::format("it was stopped by signal {}", WTERMSIG(status));
  return "it ended abnormally";
}

/// `text` for an ffmpeg image-sequence pattern, where '%' starts a conversion: "50%" → "50%%".
std::string patternLiteral(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

/// "out/penumbra.png" → "out/penumbra.mp4": the sequence's video.
std::filesystem::path videoPath(const std::string& out) { return std::filesystem::path(out).replace_extension(".mp4"); }

/// "out/penumbra.png" → "out/penumbra-0007.png" (frame 7).
std::filesystem::path framePath(const std::filesystem::path& out, int frame) {
  return out.parent_path() / fmt::format("{}-{:04d}{}", out.stem().string(), frame, out.extension().string());
}

/// Each pass's median over `frames` (the renders after the first), on stderr.
void printMedians(const PassTimings& last, const std::vector<PassTimings>& frames, const std::string& clock, const std::string& gpu) {
  for (const auto& [pass, ms] : last.ms) {
    std::vector<double> samples;
    for (const PassTimings& t : frames) samples.push_back(t.get(pass));
    std::fprintf(stderr, "penumbra: %-10s %8.2f ms\n", pass.c_str(), frames.empty() ? ms : report::timeStats(samples).median);
  }
  std::fprintf(stderr, "penumbra: times by %s on %s%s\n", clock.c_str(), gpu.c_str(),
               frames.empty() ? " (one frame: includes shader compilation)"
                              : fmt::format(" (medians of the {} frames after the first)", frames.size()).c_str());
}

/// With cached maps, what they did (--verbose).
void printMapUpdates(const Shadows& shadows) {
  if (mapsCached(shadows)) std::fprintf(stderr, "penumbra: %s\n", mapUpdatesSummary(shadows).c_str());
}

/// Renders the sequence; returns the message line of what was written.
std::string renderSequence(Renderer& renderer, const Setup& s, const std::string& out, int frames, float fps, float startS,
                           bool verbose, const std::string& gpu) {
  const std::filesystem::path first = framePath(out, 0);
  Scene posed = renderer.scene();
  std::vector<PassTimings> warm;  // the frames after the first
  for (int f = 0; f < frames; ++f) {
    poseScene(posed, startS + static_cast<float>(f) / fps);
    renderer.setPose(posed);
    renderer.render(s.render);
    if (f > 0) warm.push_back(renderer.timings());
    const ColorImage color = renderer.readColor();
    writePng(framePath(out, f), color.width, color.height, color.rgba);
  }
  if (verbose) {
    printMedians(renderer.timings(), warm, renderer.timings().clock, gpu);
    printMapUpdates(renderer.shadows());
  }
  std::string written = fmt::format("wrote {} frames {}..{} at {} fps from {} s", frames, first.string(), framePath(out, frames - 1).string(), fps, startS);
  if (renderer.scene().animation.empty()) written += " (the scene has no animation: every frame is the same)";
  const std::filesystem::path video = videoPath(out);
  const std::optional<std::filesystem::path> ffmpeg = findFfmpeg();
  if (!ffmpeg) return written + fmt::format("; no {} (ffmpeg is not on the PATH: install it for an MP4)", video.string());
  const std::filesystem::path o(out);
  const std::string pattern = (o.parent_path() / patternLiteral(o.stem().string() + "-")).string() + "%04d" +
                              patternLiteral(o.extension().string());
  // Written to a temporary name and renamed, as every output (penumbra/Files.h): the container
  // is named, since the temporary name's ending is not ".mp4".
  AtomicFile file(video);
  // yuv420p (what players expect) needs even sides: pad by one pixel where odd.
  const std::vector<std::string> argv = {ffmpeg->string(), "-y", "-loglevel", "error", "-framerate", fmt::format("{}", fps),
                                         "-i", pattern, "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
                                         "-pix_fmt", "yuv420p", "-f", "mp4", file.temporary().string()};
  if (const std::string problem = runProgram(argv); !problem.empty())
    throw Error(fmt::format("ffmpeg failed to write {}: {} (the PNG frames are written; its command: {})", video.string(), problem,
                            displayed(argv)));
  file.commit();
  return written + fmt::format(" and {}", video.string());
}

}  // namespace

void addRenderCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    TechniqueOptions technique;
    std::string out = "penumbra.png";
    std::string visibility, dump;
    int repeat = 1;
    std::optional<int> frames;
    float fps = 30.0f, timeS = 0.0f;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("render", "render one frame to a PNG (the default subcommand)");
  addTechniqueOptions(*sub, o->technique);
  addShadowBudgetOption(*sub, o->technique);
  addMapUpdatesOption(*sub, o->technique);
  sub->add_option("--out", o->out, "output PNG")->capture_default_str();
  sub->add_option("--visibility", o->visibility, "also write the visibility (1 = lit) as a float EXR");
  sub->add_option("--dump", o->dump, "write every intermediate (shadow maps, G-buffer, visibility) into this folder");
  sub->add_option("--repeat", o->repeat,
                  "render the same frame this many times and write the last (the first compiles the shaders): for "
                  "timing; --verbose then prints each pass's median over the renders after the first")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  CLI::Option* frames = sub->add_option("--frames", o->frames,
                                        "render an animated scene's frames at --time, --time + 1/--fps, ...: --out names the sequence "
                                        "(penumbra.png -> penumbra-0000.png, penumbra-0001.png, ...; and penumbra.mp4 through ffmpeg when "
                                        "it is on the PATH)")
                            ->check(CLI::Range(1, 100000));
  addTimeOptions(*sub, frames, o->fps, o->timeS, "the scene's time in seconds of the frame (of the first frame with --frames)");
  for (const char* single : {"--repeat", "--visibility", "--dump"}) frames->excludes(single);
  commands.push_back({sub, [o] {
    checkOutput("--out", o->out);
    if (!o->visibility.empty()) checkOutput("--visibility", o->visibility);
    if (!o->dump.empty()) checkOutputDir("--dump", o->dump);
    if (o->frames) {
      checkOutput("--out", framePath(o->out, *o->frames - 1).string());  // the longest name
      if (findFfmpeg()) checkOutput("--out", videoPath(o->out).string());
    }
    Setup s = makeSetup(o->technique);
    checkPoses(s.scene, sequenceTimes(o->timeS, o->frames, o->fps));
    s.render.triangleIds = false;  // nothing here traces the reference: the frame writes what it shows
    gl::HeadlessContext context({.debug = gl::kDebugBuild, .verbose = o->technique.verbose});
    checkImageFits(context, s.render.width, s.render.height,
                   kRenderHostBytesPerPixel + (o->visibility.empty() ? 0 : kVisibilityHostBytesPerPixel));
    const std::unique_ptr<Renderer> rendererPtr = makeRenderer(context, s);
    Renderer& renderer = *rendererPtr;
    if (o->frames) {
      std::printf("%s\n", renderSequence(renderer, s, o->out, *o->frames, o->fps, o->timeS, o->technique.verbose,
                                          context.info().renderer).c_str());
      return 0;
    }
    if (o->timeS != 0.0f) {
      Scene posed = renderer.scene();
      poseScene(posed, o->timeS);
      renderer.setPose(posed);
    }
    renderer.render(s.render);
    std::vector<PassTimings> warm;  // the frames after the first
    for (int i = 1; i < o->repeat; ++i) {
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
      printMedians(renderer.timings(), warm, renderer.timings().clock, context.info().renderer);
      printMapUpdates(renderer.shadows());
    }
    std::printf("wrote %s (%dx%d, scene %s, --projection %s --filter %s)\n", o->out.c_str(), color.width, color.height,
                renderer.scene().name.c_str(), renderer.technique().projection().c_str(), renderer.technique().filter().c_str());
    return 0;
  }});
}

}  // namespace penumbra::app
