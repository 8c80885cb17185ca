#pragma once
// The distance-field bake of the sdf filter (Penumbra::bake: Embree and oneTBB on the CPU,
// cached on disk). Penumbra::shadows has no baker of its own: without one, the sdf filter is
// refused. Install this one once at start-up; the filter then bakes the casters' triangles that
// Shadows::setCasterGeometry gave it (docs/sdf.md).
namespace penumbra::sdf {

/// Makes the Embree bake, with its on-disk cache, the sdf filter's baker.
void installEmbreeBaker();

}  // namespace penumbra::sdf
