#include "report/SvgChart.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra::report {
namespace {

// Layout in pixels: margins around the plot area for ticks, labels, the title and the legend.
constexpr double kMarginLeft = 64, kMarginRight = 16, kMarginTop = 34, kMarginBottom = 48;
constexpr double kLegendWidth = 170, kLegendRow = 17;
constexpr double kMarkerRadius = 4.5, kRingRadius = 8;
// A range of zero width is widened by this fraction of its value (or by 1 around 0), so that a
// single point or a flat series still gets an axis.
constexpr double kDegenerateRangeFraction = 0.1;
// Data are padded by this fraction of the range so points do not sit on the frame.
constexpr double kPadFraction = 0.05;
// A log axis with fewer 1-2-5 ticks than this in its range gets linear ones (axisTicks).
constexpr int kMinLogTicks = 3;

std::string num(double v) {
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e5 || a < 1e-3) return fmt::format("{:.0e}", v);
  return fmt::format("{}", std::round(v * 1e6) / 1e6);  // drop float noise from tick arithmetic
}

struct Axis {
  double lo = 0, hi = 1;
  bool log = false;
  double pixLo = 0, pixHi = 1;
  double map(double v) const {
    const double a = log ? std::log10(lo) : lo, b = log ? std::log10(hi) : hi, x = log ? std::log10(v) : v;
    return pixLo + (x - a) / (b - a) * (pixHi - pixLo);
  }
};

// Data range of the values usable on this axis (positive on log axes), padded.
Axis makeAxis(std::vector<double> values, bool log) {
  if (log) values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !(v > 0); }), values.end());
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }), values.end());
  Axis a;
  a.log = log;
  if (values.empty()) return a;
  a.lo = *std::min_element(values.begin(), values.end());
  a.hi = *std::max_element(values.begin(), values.end());
  if (log) {
    double l = std::log10(a.lo), h = std::log10(a.hi);
    if (h - l < 1e-9) { l -= 0.5; h += 0.5; }
    const double pad = (h - l) * kPadFraction;
    a.lo = std::pow(10.0, l - pad);
    a.hi = std::pow(10.0, h + pad);
  } else {
    if (a.hi - a.lo < 1e-12) {
      const double w = a.lo == 0.0 ? 1.0 : std::abs(a.lo) * kDegenerateRangeFraction;
      a.lo -= w;
      a.hi += w;
    }
    const double pad = (a.hi - a.lo) * kPadFraction;
    // Keep a zero baseline when the data start near it (times, errors are never negative).
    a.lo = a.lo >= 0.0 && a.lo - pad < 0.0 ? 0.0 : a.lo - pad;
    a.hi += pad;
  }
  return a;
}

std::string markerSvg(Marker m, double x, double y, const std::string& color, double r = kMarkerRadius) {
  switch (m) {
    case Marker::Square:
      return fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="{}"/>)", x - r, y - r, 2 * r, 2 * r, color);
    case Marker::Triangle:
      return fmt::format(R"(<polygon points="{:.1f},{:.1f} {:.1f},{:.1f} {:.1f},{:.1f}" fill="{}"/>)", x, y - r * 1.2,
                         x - r * 1.1, y + r * 0.8, x + r * 1.1, y + r * 0.8, color);
    case Marker::Diamond:
      return fmt::format(R"(<polygon points="{:.1f},{:.1f} {:.1f},{:.1f} {:.1f},{:.1f} {:.1f},{:.1f}" fill="{}"/>)", x,
                         y - r * 1.3, x + r * 1.3, y, x, y + r * 1.3, x - r * 1.3, y, color);
    case Marker::TriangleDown:
      return fmt::format(R"(<polygon points="{:.1f},{:.1f} {:.1f},{:.1f} {:.1f},{:.1f}" fill="{}"/>)", x, y + r * 1.2,
                         x - r * 1.1, y - r * 0.8, x + r * 1.1, y - r * 0.8, color);
    case Marker::Star: {  // five points
      std::string pts;
      for (int k = 0; k < 10; ++k) {
        const double a = 3.14159265358979 * (0.5 + 0.2 * k), rr = k % 2 == 0 ? r * 1.35 : r * 0.6;
        pts += fmt::format("{:.1f},{:.1f} ", x + rr * std::cos(a), y - rr * std::sin(a));
      }
      return fmt::format(R"(<polygon points="{}" fill="{}"/>)", pts, color);
    }
    case Marker::Cross:  // an x: a point set apart (tune: beyond the bars)
      return fmt::format(R"(<path d="M{0:.1f},{1:.1f}L{2:.1f},{3:.1f}M{0:.1f},{3:.1f}L{2:.1f},{1:.1f}" stroke="{4}" stroke-width="2"/>)",
                         x - r, y - r, x + r, y + r, color);
    case Marker::Circle:
    default:
      return fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="{:.1f}" fill="{}"/>)", x, y, r, color);
  }
}

}  // namespace

std::string escapeXml(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::vector<double> axisTicks(double lo, double hi, bool log, int target) {
  std::vector<double> ticks;
  if (!(hi > lo)) return ticks;
  if (log) {
    const int a = static_cast<int>(std::floor(std::log10(lo))), b = static_cast<int>(std::ceil(std::log10(hi)));
    const bool fine = std::log10(hi / lo) < 3.0;
    for (int e = a; e <= b; ++e)
      for (const double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back(v);
      }
    // Within a decade the 1-2-5 values leave one tick or none (24 … 46 holds none): round linear
    // steps label such a narrow log axis instead.
    if (static_cast<int>(ticks.size()) < kMinLogTicks) return axisTicks(lo, hi, false, target);
    return ticks;
  }
  const double raw = (hi - lo) / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / mag < 1.5 ? mag : raw / mag < 3.5 ? 2 * mag : raw / mag < 7.5 ? 5 * mag : 10 * mag;
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return ticks;
}

std::string paletteColor(size_t index) {
  // No grey: the legend draws projection markers in grey.
  static const char* const kColors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9",
                                        "#000000", "#8C564B", "#6A3D9A", "#BCBD22", "#17BECF", "#FB9A99"};
  return kColors[index % std::size(kColors)];
}

std::string svgChart(const Chart& c) {
  const double plotRight = c.width - kMarginRight - (c.legend.empty() ? 0 : kLegendWidth);
  const double plotBottom = c.height - kMarginBottom;
  std::string s = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" class="chart" role="img" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="11">)"
      "<title>{2}</title>\n",
      c.width, c.height, escapeXml(c.title));
  s += fmt::format(R"(<text x="{}" y="18" font-size="13" font-weight="bold">{}</text>)", kMarginLeft, escapeXml(c.title));
  std::vector<double> xs, ys;
  for (const ChartSeries& series : c.series)
    for (const ChartPoint& p : series.points) {
      xs.push_back(p.x);
      ys.push_back(p.y);
      if (std::isfinite(p.yLow)) ys.push_back(p.yLow);
      if (std::isfinite(p.yHigh)) ys.push_back(p.yHigh);
    }
  if (xs.empty()) {
    s += fmt::format(R"(<text x="{}" y="{}" fill="#666">no data in this run</text></svg>)", kMarginLeft, c.height / 2);
    return s + "\n";
  }
  Axis ax = makeAxis(xs, c.logX), ay = makeAxis(ys, c.logY);
  ax.pixLo = kMarginLeft;
  ax.pixHi = plotRight;
  ay.pixLo = plotBottom;
  ay.pixHi = kMarginTop;
  auto usable = [&](double x, double y) { return std::isfinite(x) && std::isfinite(y) && (!c.logX || x > 0) && (!c.logY || y > 0); };

  // Frame, grid and ticks.
  s += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="#fff" stroke="#999"/>)", kMarginLeft,
                   kMarginTop, plotRight - kMarginLeft, plotBottom - kMarginTop);
  for (const double t : axisTicks(ax.lo, ax.hi, c.logX)) {
    const double x = ax.map(t);
    s += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="#e4e4e4"/>)", x, kMarginTop, plotBottom);
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>)", x, plotBottom + 14, num(t));
  }
  for (const double t : axisTicks(ay.lo, ay.hi, c.logY)) {
    const double y = ay.map(t);
    s += fmt::format(R"(<line x1="{0:.1f}" y1="{2:.1f}" x2="{1:.1f}" y2="{2:.1f}" stroke="#e4e4e4"/>)", kMarginLeft, plotRight, y);
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end">{}</text>)", kMarginLeft - 4, y + 4, num(t));
  }
  s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>)", (kMarginLeft + plotRight) / 2,
                   c.height - 10.0, escapeXml(c.xLabel));
  s += fmt::format(R"svg(<text transform="translate(14 {:.1f}) rotate(-90)" text-anchor="middle">{}</text>)svg",
                   (kMarginTop + plotBottom) / 2, escapeXml(c.yLabel));

  // The front as a staircase: each point's y holds until the next point's x.
  if (c.front.size() > 0) {
    std::string path;
    for (size_t i = 0; i < c.front.size(); ++i) {
      const auto [fx, fy] = c.front[i];
      if (!usable(fx, fy)) continue;
      path += fmt::format("{}{:.1f},{:.1f} ", path.empty() ? "M" : "L", ax.map(fx), ay.map(fy));
      if (i + 1 < c.front.size() && usable(c.front[i + 1].first, fy))
        path += fmt::format("L{:.1f},{:.1f} ", ax.map(c.front[i + 1].first), ay.map(fy));
    }
    s += fmt::format(R"(<path class="front" d="{}" fill="none" stroke="{}" stroke-width="1.5" stroke-dasharray="5,3"/>)", path, kFrontColor);
  }

  for (const ChartSeries& series : c.series) {
    std::vector<ChartPoint> pts;
    for (const ChartPoint& p : series.points)
      if (usable(p.x, p.y)) pts.push_back(p);
    std::sort(pts.begin(), pts.end(), [](const ChartPoint& a, const ChartPoint& b) { return a.x < b.x; });
    if (series.connect && pts.size() > 1) {
      std::string pl;
      for (const ChartPoint& p : pts) pl += fmt::format("{:.1f},{:.1f} ", ax.map(p.x), ay.map(p.y));
      s += fmt::format(R"(<polyline points="{}" fill="none" stroke="{}" stroke-width="1.5"/>)", pl, series.color);
    }
    for (const ChartPoint& p : pts) {
      const double x = ax.map(p.x), y = ay.map(p.y);
      s += "<g>";
      if (!p.tooltip.empty()) s += "<title>" + escapeXml(p.tooltip) + "</title>";
      if (usable(p.x, p.yLow) && usable(p.x, p.yHigh))
        s += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="{3}"/>)", x, ay.map(p.yLow),
                         ay.map(p.yHigh), series.color);
      if (p.emphasised)
        s += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="{:.1f}" fill="none" stroke="#000" stroke-width="1.2"/>)", x, y, kRingRadius);
      s += markerSvg(series.marker, x, y, series.color);
      if (!p.tag.empty())
        s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="9" fill="#333">{}</text>)", x + kMarkerRadius + 1.5,
                         y - kMarkerRadius + 1.0, escapeXml(p.tag));
      s += "</g>\n";
    }
  }

  // Legend, right of the plot.
  double ly = kMarginTop + 6;
  for (const LegendEntry& e : c.legend) {
    const double lx = plotRight + 14;
    if (e.line)
      s += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{2:.1f}" y2="{1:.1f}" stroke="{3}" stroke-width="1.5" stroke-dasharray="{4}"/>)",
                       lx - 6, ly, lx + 6, e.color, e.dashed ? "5,3" : "none");
    else if (!e.tag.empty())
      s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" font-size="9" fill="#333">{}</text>)", lx, ly + 3,
                       escapeXml(e.tag));
    else
      s += markerSvg(e.marker, lx, ly, e.color);
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}">{}</text>)", lx + 12, ly + 4, escapeXml(e.label));
    ly += kLegendRow;
  }
  return s + "</svg>\n";
}

std::string svgBarChart(const BarChart& c) {
  // Rows of kBarRow pixels: the label column, the bars, then room for the value text.
  constexpr double kBarRow = 16, kBarHeight = 11, kLabelWidth = 230, kValueWidth = 150, kLegendHeight = 22;
  constexpr double kTitleHeight = 24, kAxisHeight = 36;
  const double top = kTitleHeight + kLegendHeight, left = kLabelWidth, right = c.width - kValueWidth;
  const double bottom = top + kBarRow * static_cast<double>(c.bars.size());
  const double height = bottom + kAxisHeight;
  std::string s = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" class="chart bars" role="img" width="{0}" height="{1:.0f}" viewBox="0 0 {0} {1:.0f}" font-family="sans-serif" font-size="11">)"
      "<title>{2}</title>\n",
      c.width, height, escapeXml(c.title));
  s += fmt::format(R"(<text x="4" y="16" font-size="13" font-weight="bold">{}</text>)", escapeXml(c.title));
  double lx = 4;
  for (const LegendEntry& e : c.legend) {
    s += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="12" height="10" fill="{}"/>)", lx, kTitleHeight + 2, e.color);
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}">{}</text>)", lx + 16, kTitleHeight + 11, escapeXml(e.label));
    lx += 16 + 7.0 * static_cast<double>(e.label.size()) + 18;
  }
  double maxValue = 0.0;
  for (const Bar& b : c.bars) {
    double sum = 0.0;
    for (const BarSegment& g : b.segments) sum += std::max(0.0, g.value);
    maxValue = std::max({maxValue, sum, std::isfinite(b.mark) ? b.mark : 0.0});
  }
  if (c.bars.empty() || !(maxValue > 0.0)) {
    s += fmt::format(R"(<text x="{}" y="{}" fill="#666">no data in this run</text></svg>)", left, top + 14);
    return s + "\n";
  }
  Axis ax = makeAxis({0.0, maxValue}, false);
  ax.pixLo = left;
  ax.pixHi = right;
  for (const double t : axisTicks(ax.lo, ax.hi, false)) {
    const double x = ax.map(t);
    s += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="#e4e4e4"/>)", x, top, bottom);
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>)", x, bottom + 14, num(t));
  }
  s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>)", (left + right) / 2, height - 6,
                   escapeXml(c.xLabel));
  double y = top;
  for (const Bar& b : c.bars) {
    const double barY = y + (kBarRow - kBarHeight) / 2;
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end">{}</text>)", left - 6, y + 12, escapeXml(b.label));
    double v = 0.0;
    for (const BarSegment& g : b.segments) {
      const double w = std::max(0.0, g.value);
      s += "<g>";
      if (!g.tooltip.empty()) s += "<title>" + escapeXml(g.tooltip) + "</title>";
      s += fmt::format(R"(<rect x="{:.2f}" y="{:.1f}" width="{:.2f}" height="{:.1f}" fill="{}"/>)", ax.map(v), barY,
                       ax.map(v + w) - ax.map(v), kBarHeight, g.color);
      s += "</g>";
      v += w;
    }
    if (std::isfinite(b.mark)) {
      s += "<g>";
      if (!b.markTooltip.empty()) s += "<title>" + escapeXml(b.markTooltip) + "</title>";
      s += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="#000" stroke-width="2"/>)",
                       ax.map(b.mark), barY - 2, barY + kBarHeight + 2);
      s += "</g>";
    }
    s += fmt::format(R"(<text x="{:.1f}" y="{:.1f}">{}</text>)", ax.map(std::max(v, std::isfinite(b.mark) ? b.mark : 0.0)) + 6,
                     y + 12, escapeXml(b.valueText));
    s += "\n";
    y += kBarRow;
  }
  return s + "</svg>\n";
}

}  // namespace penumbra::report
