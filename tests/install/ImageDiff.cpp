// penumbra_image_diff A.png B.png [--max-mean X] [--max-over-pct Y] [--threshold T]
// Compares two images of the same size channel by channel (RGB, 0–255): prints the mean absolute
// difference, the largest, and the share of pixels where some channel differs by more than T
// (default 8, about 3 %); exits 1 when the mean exceeds X or that share exceeds Y %.
#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: penumbra_image_diff A.png B.png [--max-mean X] [--max-over-pct Y] [--threshold T]\n");
    return 2;
  }
  double maxMean = 1e30, maxOverPct = 100.0;
  int threshold = 8;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--max-mean") maxMean = std::atof(argv[i + 1]);
    else if (a == "--max-over-pct") maxOverPct = std::atof(argv[i + 1]);
    else if (a == "--threshold") threshold = std::atoi(argv[i + 1]);
    else { std::fprintf(stderr, "unknown option %s\n", a.c_str()); return 2; }
  }
  try {
    int wa = 0, ha = 0, wb = 0, hb = 0;
    const std::vector<uint8_t> a = penumbra::readPng(argv[1], wa, ha), b = penumbra::readPng(argv[2], wb, hb);
    if (wa != wb || ha != hb) {
      std::fprintf(stderr, "sizes differ: %dx%d against %dx%d\n", wa, ha, wb, hb);
      return 1;
    }
    const size_t pixels = static_cast<size_t>(wa) * static_cast<size_t>(ha);
    double sum = 0.0;
    int largest = 0;
    size_t over = 0;
    for (size_t p = 0; p < pixels; ++p) {
      int worst = 0;
      for (size_t c = 0; c < 3; ++c) {
        const int d = std::abs(int(a[p * 4 + c]) - int(b[p * 4 + c]));
        sum += d;
        worst = std::max(worst, d);
      }
      largest = std::max(largest, worst);
      if (worst > threshold) ++over;
    }
    const double mean = sum / (3.0 * static_cast<double>(pixels));
    const double overPct = 100.0 * static_cast<double>(over) / static_cast<double>(pixels);
    std::printf("%dx%d: mean |difference| %.3f of 255, largest %d, %.3f %% of pixels differ by more than %d\n", wa, ha, mean,
                largest, overPct, threshold);
    if (mean > maxMean || overPct > maxOverPct) {
      std::fprintf(stderr, "over the bounds (mean <= %g, share <= %g %%)\n", maxMean, maxOverPct);
      return 1;
    }
    return 0;
  } catch (const penumbra::Error& e) {
    std::fprintf(stderr, "penumbra_image_diff: %s\n", e.what());
    return 1;
  }
}
