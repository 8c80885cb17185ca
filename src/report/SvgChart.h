#pragma once
// Charts as inline SVG text, written by hand (no JavaScript, no library): axes with "nice"
// ticks (linear or logarithmic), points with optional error bars and hover titles, optional
// connecting lines, a highlighted polyline (the Pareto front) and a legend.
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::report {

enum class Marker { Circle, Square, Triangle, Diamond, TriangleDown, Star, Cross };

/// Colour of Chart::front (a legend entry for it uses this with line + dashed).
inline constexpr const char* kFrontColor = "#444";

struct ChartPoint {
  double x = 0.0, y = 0.0;
  /// Error bar from yLow to yHigh (both NaN = none).
  double yLow = std::numeric_limits<double>::quiet_NaN(), yHigh = std::numeric_limits<double>::quiet_NaN();
  std::string tooltip;     ///< shown on hover (an SVG <title>)
  bool emphasised = false; ///< drawn with a ring (e.g. on the Pareto front)
  std::string tag = {};    ///< a short text beside the marker (the report: the projection's letter)
};

struct ChartSeries {
  std::string color = "#333";  ///< CSS colour
  Marker marker = Marker::Circle;
  bool connect = false;        ///< a line through the points in x order
  std::vector<ChartPoint> points;
};

struct LegendEntry {
  std::string label, color;
  Marker marker = Marker::Circle;
  bool line = false;    ///< a line sample instead of a marker
  bool dashed = false;  ///< the line sample dashed (the front's style)
  std::string tag = {}; ///< a text sample instead of a marker (a point's ChartPoint::tag)
};

struct Chart {
  std::string title, xLabel, yLabel;
  bool logX = false, logY = false;  ///< log axes skip non-positive values
  int width = 600, height = 400;    ///< pixels, legend included (two fit side by side in the report)
  std::vector<ChartSeries> series;
  /// A polyline drawn under the points as a staircase (e.g. the Pareto front), in x order.
  std::vector<std::pair<double, double>> front;
  std::vector<LegendEntry> legend;
};

/// The chart as an <svg> element (role="img", with a <title>). Empty charts get a note instead
/// of axes.
std::string svgChart(const Chart& chart);

/// One part of a stacked bar (e.g. one pass's time).
struct BarSegment {
  double value = 0.0;
  std::string color;
  std::string tooltip;
};

/// A horizontal bar of stacked segments, with a label on its left, text on its right, and an
/// optional tick across it at `mark` (e.g. a statistic of the whole that is not the segments' sum).
struct Bar {
  std::string label, valueText;
  std::vector<BarSegment> segments;
  double mark = std::numeric_limits<double>::quiet_NaN();
  std::string markTooltip;
};

/// Horizontal stacked bars on a linear axis from 0, one row each, a legend above them. The
/// height follows the number of bars.
struct BarChart {
  std::string title, xLabel;
  int width = 1200;  ///< pixels
  std::vector<Bar> bars;
  std::vector<LegendEntry> legend;  ///< drawn as swatches (marker and line are ignored)
};
std::string svgBarChart(const BarChart& chart);

/// Text escaped for XML/HTML content and attribute values.
std::string escapeXml(std::string_view text);

/// Tick values for [lo, hi]: 1-2-5 steps, about `target` of them (linear), or powers of ten
/// (with 2 and 5 between when the range spans less than three decades) for log axes; a log
/// range that holds fewer than three of those (24 … 46) gets the linear ticks.
std::vector<double> axisTicks(double lo, double hi, bool log, int target = 6);

/// A fixed set of distinguishable colours (Okabe–Ito first), cycled by index.
std::string paletteColor(size_t index);

}  // namespace penumbra::report
