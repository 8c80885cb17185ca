#pragma once
// Sampling patterns shared by the filters that look around a point of a shadow map (PCF, PCSS
// blocker search and filtering, soft-shadow variants): a progressive Poisson disk, a per-pixel
// rotation that turns its structured error into fine noise, and a regular box grid. Offsets are
// in the unit disk / unit square; the caller scales them to a radius in map uv.

// 64 points in the unit disk from Mitchell's best-candidate algorithm (each point the farthest
// of many random candidates from the points before it and, at 2.5x weight, from the rim). Every
// prefix is itself well spread, so the first n points serve as an n-tap disk for any n <= 64;
// mean squared radius 0.42..0.49 for n = 8..64 (0.5 = uniform over the disk).
const int kPoissonDiskSize = 64;
const vec2 kPoissonDisk[kPoissonDiskSize] = vec2[](
    vec2(-0.3523, -0.6983), vec2(0.3906, 0.1887), vec2(-0.5189, 0.1729), vec2(0.3651, -0.6038),
    vec2(-0.0610, 0.6794), vec2(-0.6910, -0.3260), vec2(-0.1003, -0.2287), vec2(0.8144, -0.0038),
    vec2(0.4860, 0.6420), vec2(-0.5018, 0.6299), vec2(0.3901, -0.2078), vec2(0.0289, -0.7913),
    vec2(-0.1057, 0.2805), vec2(0.7668, -0.3619), vec2(0.7465, 0.3739), vec2(-0.7641, 0.3980),
    vec2(-0.8363, 0.0000), vec2(0.1848, 0.4422), vec2(0.1252, -0.0021), vec2(0.2243, 0.8217),
    vec2(-0.4358, -0.1294), vec2(0.1217, -0.4345), vec2(-0.3216, -0.3959), vec2(0.6492, -0.6173),
    vec2(-0.2920, 0.8382), vec2(-0.6320, -0.6105), vec2(-0.1949, 0.0284), vec2(-0.3277, 0.4305),
    vec2(0.5606, -0.0037), vec2(0.2725, -0.8264), vec2(-0.1162, -0.5435), vec2(0.5195, -0.4130),
    vec2(0.5088, 0.3903), vec2(-0.2259, -0.8761), vec2(-0.0198, 0.9001), vec2(-0.8839, -0.2200),
    vec2(0.1096, 0.2283), vec2(-0.6474, -0.1141), vec2(0.6757, 0.1768), vec2(-0.5354, 0.3934),
    vec2(-0.8925, 0.2095), vec2(0.1638, -0.2188), vec2(0.8932, 0.2029), vec2(0.6136, -0.2086),
    vec2(0.6910, 0.5995), vec2(-0.2988, 0.6320), vec2(-0.3077, 0.2070), vec2(0.4795, -0.7750),
    vec2(-0.0441, 0.4796), vec2(0.3433, -0.0042), vec2(0.2650, 0.6250), vec2(0.1513, -0.6302),
    vec2(0.3279, -0.3987), vec2(-0.5132, -0.4398), vec2(0.8931, -0.2031), vec2(-0.7021, 0.5773),
    vec2(-0.7055, 0.1774), vec2(0.4241, 0.8162), vec2(-0.5249, -0.7588), vec2(-0.7690, -0.4940),
    vec2(0.3550, 0.4737), vec2(-0.3862, 0.0482), vec2(-0.1639, -0.7027), vec2(-0.2602, -0.1510));

// Point i of an n-point sunflower spiral in the unit disk (Vogel 1979): radius √((i + ½) / n),
// each point a golden angle (π(3 − √5) rad) on from the last. Every point stands for an equal
// share of the disk's area, for any n, so n points sample a uniformly bright disk without the
// Poisson prefix's pull toward the centre (mean r² exactly ½); turned per pixel like the disk.
vec2 sunflowerDiskTap(int i, int n) {
  const float kGoldenAngleRad = 2.39996322973;
  float r = sqrt((float(i) + 0.5) / float(n));
  float a = float(i) * kGoldenAngleRad;
  return r * vec2(cos(a), sin(a));
}

// Interleaved gradient noise (Jimenez 2014): a per-pixel value in [0,1) whose neighbours differ
// a lot, so per-pixel rotations decorrelate across a few pixels instead of forming bands.
float interleavedGradientNoise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// The pixel's noise in frame `frame` of an accumulated sequence (temporal.*, docs/temporal.md):
// advanced by the golden ratio each frame, so the values one pixel takes over successive frames
// spread evenly over [0,1). Frame 0 is the plain per-pixel noise, bit for bit (what every frame
// uses when nothing accumulates).
float pixelNoise(ivec2 pixel, int frame) {
  float noise = interleavedGradientNoise(vec2(pixel));
  const float kGoldenRatioFraction = 0.61803398875;  // the most evenly spreading step mod 1
  return frame == 0 ? noise : fract(noise + float(frame) * kGoldenRatioFraction);
}

// A rotation by a per-pixel angle: rotating the disk per pixel trades the banding of one fixed
// pattern for noise (Poisson-disk PCF's usual choice); a frame index other than 0 turns it on
// further each frame, so that accumulating frames averages different taps.
mat2 pixelRotation(ivec2 pixel, int frame) {
  float angle = 6.28318530718 * pixelNoise(pixel, frame);
  float c = cos(angle), s = sin(angle);
  return mat2(c, s, -s, c);
}

// Number of taps of a (2·halfSide + 1)² box grid.
int boxTapCount(int halfSide) { return (2 * halfSide + 1) * (2 * halfSide + 1); }

// Tap i (< boxTapCount(halfSide)) of the box grid: a point of [-1,1]², row by row; spacing
// 1/halfSide, so halfSide = r gives one tap per texel for a radius of r texels. halfSide 0 is
// the single centre tap.
vec2 boxTap(int i, int halfSide) {
  int side = 2 * halfSide + 1;
  vec2 cell = vec2(float(i % side), float(i / side)) - float(halfSide);
  return halfSide > 0 ? cell / float(halfSide) : vec2(0.0);
}

// The largest box grid with at most `taps` taps (at least the centre tap).
int boxHalfSideForTaps(int taps) {
  int halfSide = 0;
  while (boxTapCount(halfSide + 1) <= taps) ++halfSide;
  return halfSide;
}
