#pragma once
// The viewer's error heatmap and reference: H (or the Tools tab) traces the Embree reference of
// the frame on the screen on a background thread (HeatmapJob) and shows V − V_ref over it; R
// flips the view between the technique and the same frame lit with V_ref (traced first when
// there is none of this view). It owns the job, the two images and their metrics; the panels,
// the legends and the script take it by reference.
#include "viewer/HeatmapJob.h"
#include "viewer/StatusLine.h"

#include "gl/Objects.h"

#include <penumbra/Reference.h>

#include <cstdint>
#include <optional>
#include <string>

namespace penumbra::viewer {

class ViewSession;

/// Names of the two images it adds to the views.
inline constexpr const char* kHeatmapView = "heatmap";
/// The same frame lit with the reference's V_ref (after a heatmap of this view): R flips to it.
inline constexpr const char* kReferenceView = "reference";

class HeatmapView {
public:
  HeatmapView(ViewSession& session, StatusLine& status, bool scripted) : mSession(session), mStatus(status), mScripted(scripted) {}
  ~HeatmapView() { mJob.cancel(); }

  /// A trace at `samples` (default: the Tools tab's) of the frame drawn next.
  void request(std::optional<int> samples = std::nullopt) { mRequest = samples.value_or(mSamples); }
  /// After the frame rendered: starts the requested trace on it. `shaded` = the main view is
  /// the shaded picture (the heatmap's backdrop; a lit-pass debug view would mislead).
  void startRequested(bool shaded);
  /// Takes a finished trace (the images made); returns the view the main slot shows then:
  /// the heatmap, or the reference when R asked for it. Throws a failed trace's Error when scripted.
  std::optional<std::string> poll();
  /// R, with the main slot showing `mainView`: the view to show now, or nothing when the
  /// reference of this view is being traced first (poll() shows it).
  std::optional<std::string> flip(const std::string& mainView);
  /// A new scene: the running trace cancelled, the reference is another scene's.
  void forgetScene();
  /// Running, requested, or finished with its result not yet taken by poll(): what the script's
  /// `wait-heatmap` waits on, so that the reference it traced is there after it (a flip right
  /// after it, under load, found none and traced again).
  bool busy() const { return mJob.running() || mRequest.has_value() || mJob.untaken(); }

  /// The heatmap or the reference image by view name; null when there is none (yet).
  const gl::Texture* image(const std::string& name) const;
  /// True for its own images (colour images, shown as they are).
  bool owns(const gl::Texture* texture) const { return texture == &mHeatmap || texture == &mReference; }
  int samplesShown() const { return mResult ? mResult->samplesPerPixel : 0; }

  /// The progress box over the view's top-left corner (`viewLeftPx`: ImGui display pixels).
  void drawProgress(float viewLeftPx);
  /// The Tools tab's heatmap half: samples, start/cancel, the metrics, staleness.
  void drawControls();

private:
  ViewSession& mSession;
  StatusLine& mStatus;
  bool mScripted;
  HeatmapJob mJob;
  std::optional<HeatmapResult> mResult;
  gl::Texture mHeatmap;
  int mSamples = ReferenceOptions{}.samples;  ///< as compare and bench: the same ruler
  std::optional<int> mRequest;                ///< samples; started once this frame is rendered
  gl::Texture mReference;                     ///< the heatmap's frame lit with V_ref
  uint64_t mReferenceVersion = 0;             ///< ViewSession::version() it shows (0 = none)
  bool mFlipWhenReady = false;                ///< R pressed before a heatmap of this view existed
};

}  // namespace penumbra::viewer
