#pragma once
// The 16-bit quantisation transform of four depth moments (Peters & Klein 2015, "Moment Shadow
// Mapping", the optimised basis): b = (z, z^2, z^3, z^4) for z in [0, 1] is mapped by an affine
// transform q = M·b + o into [0, 1]^4 such that rounding q to 16 bits disturbs the moment vector
// far less than rounding b itself (b's four coordinates are nearly collinear). Both directions are
// affine, so filtering (mip maps, SATs) commutes with them.
// Compiled as C++ (the shadow pass clears its target to the encoded value of z = 1) and GLSL.
// Columns are listed first, as both glm::mat4 and GLSL mat4 take them: q = M * b.

#define PN_MSM16_ENCODE_MATRIX                                          \
  -2.07224649, 13.7948857237, 0.105877704, 9.7924062118,                \
  32.23703778, -59.4683975703, -1.9077466311, -33.7652110555,           \
  -68.571074599, 82.0359750338, 9.3496555107, 47.9456096605,            \
  39.3703274134, -35.364903257, -6.6543490743, -23.9728048165
#define PN_MSM16_ENCODE_OFFSET_X 0.035955884801
// b = D * (q - (offset, 0, 0, 0)): the inverse of the encode matrix.
#define PN_MSM16_DECODE_MATRIX                                          \
  0.2227744146, 0.1549679261, 0.1451988946, 0.163127443,                \
  0.0771972861, 0.1394629426, 0.2120202157, 0.2591432266,               \
  0.7926986636, 0.7963415838, 0.7258694464, 0.6539092497,               \
  0.0319417555, -0.1722823173, -0.2758014811, -0.3376131734
