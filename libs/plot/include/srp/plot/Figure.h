#pragma once
/// \file Figure.h
/// \brief Small 2D charts written as PNG (line, scatter, vertical markers,
/// shaded bands, legends, subplot grids), drawn with OpenCV, for reports, experiments and
/// notebooks. No display needed.
///
/// \code
///   srp::plot::Figure fig(900, 600, 2, 1);            // 2 rows, 1 column
///   auto& ax = fig.axes(0, 0);
///   ax.title = "Hand trajectory";  ax.xLabel = "t [s]";  ax.yLabel = "x [m]";
///   ax.line(t, x, "demo");
///   ax.line(t, xr, "reproduction", srp::plot::Colour::tab(1), 2.0, true);  // dashed
///   ax.verticalLine(3.2, "grasp");
///   fig.save("hand.png");
/// \endcode

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace srp::plot {

/// sRGB colour, 0-255.
struct Colour {
  int r = 0, g = 0, b = 0;
  /// The i-th colour of matplotlib's tab10 palette (cycles).
  static Colour tab(int i);
  static Colour gray() { return {120, 120, 120}; }
};

enum class Marker { None, Circle, Cross, Square, Triangle };

/// One data series of an Axes.
struct Series {
  std::string label;           ///< empty: not in the legend
  std::vector<double> x, y;
  Colour colour;
  double lineWidth_px = 2.0;   ///< 0: no line
  bool dashed = false;
  Marker marker = Marker::None;
  double markerSize_px = 4.0;
};

/// One chart: series, vertical/horizontal reference lines, labels, limits.
class Axes {
 public:
  std::string title, xLabel, yLabel;
  std::optional<std::pair<double, double>> xLimits, yLimits;  ///< default: data range + margin
  bool equalAspect = false;  ///< same metres per pixel on both axes (top views)
  bool legend = true;

  Series& line(std::vector<double> x, std::vector<double> y, std::string label = "",
               std::optional<Colour> colour = std::nullopt, double width_px = 2.0, bool dashed = false);
  Series& scatter(std::vector<double> x, std::vector<double> y, std::string label = "",
                  std::optional<Colour> colour = std::nullopt, Marker marker = Marker::Circle, double size_px = 4.0);
  void verticalLine(double x, std::string label = "", std::optional<Colour> colour = std::nullopt, bool dashed = true);
  void horizontalLine(double y, std::string label = "", std::optional<Colour> colour = std::nullopt, bool dashed = true);
  /// A shaded vertical band over x in [x0, x1] (a phase, an interval), drawn
  /// under the data and blended with the background at `opacity` (0-1); a
  /// labelled band gets a filled square in the legend. Throws
  /// InvalidInputError when x0 > x1, a bound is not finite or opacity is outside [0, 1].
  void band(double x0, double x1, std::string label = "", std::optional<Colour> colour = std::nullopt,
            double opacity = 0.2);

  const std::vector<Series>& series() const { return series_; }
  struct RefLine { bool vertical; double value; std::string label; Colour colour; bool dashed; };
  const std::vector<RefLine>& refLines() const { return refLines_; }
  struct Band { double x0, x1; std::string label; Colour colour; double opacity; };
  const std::vector<Band>& bands() const { return bands_; }

 private:
  Colour nextColour() { return Colour::tab(static_cast<int>(series_.size())); }
  std::vector<Series> series_;
  std::vector<RefLine> refLines_;
  std::vector<Band> bands_;
};

/// A grid of Axes rendered to one image.
class Figure {
 public:
  Figure(int width_px, int height_px, int rows = 1, int cols = 1);
  Axes& axes(int row = 0, int col = 0);
  std::string title;  ///< drawn above the grid when not empty

  /// Renders and writes a PNG; throws srp::core::FileError naming the path on failure.
  void save(const std::string& pngPath) const;
  /// Renders to PNG bytes.
  std::vector<unsigned char> encodePng() const;

 private:
  int width_px_, height_px_, rows_, cols_;
  std::vector<Axes> axes_;
};

}  // namespace srp::plot
