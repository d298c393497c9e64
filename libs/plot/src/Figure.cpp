#include "srp/plot/Figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"

namespace srp::plot {

Colour Colour::tab(int i) {
  static const Colour kTab10[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},  {148, 103, 189},
                                 {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
  return kTab10[((i % 10) + 10) % 10];
}

Series& Axes::line(std::vector<double> x, std::vector<double> y, std::string label, std::optional<Colour> colour,
                   double width_px, bool dashed) {
  if (x.size() != y.size()) throw core::InvalidInputError("plot series '" + label + "': x and y differ in length");
  Series s{std::move(label), std::move(x), std::move(y), colour.value_or(nextColour()), width_px, dashed};
  series_.push_back(std::move(s));
  return series_.back();
}

Series& Axes::scatter(std::vector<double> x, std::vector<double> y, std::string label, std::optional<Colour> colour,
                      Marker marker, double size_px) {
  Series& s = line(std::move(x), std::move(y), std::move(label), colour, 0.0, false);
  s.marker = marker;
  s.markerSize_px = size_px;
  return s;
}

void Axes::verticalLine(double x, std::string label, std::optional<Colour> colour, bool dashed) {
  refLines_.push_back({true, x, std::move(label), colour.value_or(Colour::gray()), dashed});
}

void Axes::horizontalLine(double y, std::string label, std::optional<Colour> colour, bool dashed) {
  refLines_.push_back({false, y, std::move(label), colour.value_or(Colour::gray()), dashed});
}

void Axes::band(double x0, double x1, std::string label, std::optional<Colour> colour, double opacity) {
  if (!std::isfinite(x0) || !std::isfinite(x1) || x0 > x1)
    throw core::InvalidInputError("plot band '" + label + "': needs finite bounds with x0 <= x1");
  if (!(opacity >= 0.0 && opacity <= 1.0))
    throw core::InvalidInputError("plot band '" + label + "': opacity must be in [0, 1]");
  bands_.push_back({x0, x1, std::move(label), colour.value_or(Colour::gray()), opacity});
}

Figure::Figure(int width_px, int height_px, int rows, int cols)
    : width_px_(width_px), height_px_(height_px), rows_(rows), cols_(cols),
      axes_(static_cast<std::size_t>(rows * cols)) {
  if (width_px < 100 || height_px < 100 || rows < 1 || cols < 1)
    throw core::InvalidInputError("figure must be at least 100x100 px with at least one row and column");
}

Axes& Figure::axes(int row, int col) {
  if (row < 0 || row >= rows_ || col < 0 || col >= cols_)
    throw core::InvalidInputError("figure has no axes (" + std::to_string(row) + ", " + std::to_string(col) + ")");
  return axes_[static_cast<std::size_t>(row * cols_ + col)];
}

namespace {

const cv::Scalar kBlack(0, 0, 0), kGrid(225, 225, 225), kWhite(255, 255, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

cv::Scalar bgr(const Colour& c) { return cv::Scalar(c.b, c.g, c.r); }

// "Nice" tick step (1, 2 or 5 x 10^k) for about `count` ticks over `span`.
double tickStep(double span, int count) {
  const double raw = span / std::max(1, count);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag) return m * mag;
  return 10 * mag;
}

std::string tickLabel(double v, double step) {
  char buf[32];
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 6), std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buf;
}

void text(cv::Mat& img, const std::string& s, cv::Point p, double scale, const cv::Scalar& c, int align = 0) {
  int base = 0;
  const cv::Size sz = cv::getTextSize(s, kFont, scale, 1, &base);
  if (align == 1) p.x -= sz.width / 2;
  if (align == 2) p.x -= sz.width;
  cv::putText(img, s, p, kFont, scale, c, 1, cv::LINE_AA);
}

// Draws a -> b dashed (8 px on, 6 px off); `phase` carries the pattern across
// the segments of a polyline so short segments still show dashes.
void dashedLine(cv::Mat& img, cv::Point2d a, cv::Point2d b, const cv::Scalar& c, int width, double* phase = nullptr) {
  constexpr double kOn = 8.0, kPeriod = 14.0;
  double local = 0.0;
  double& s = phase ? *phase : local;
  const double len = cv::norm(b - a);
  if (len < 1e-9) return;
  double done = 0.0;
  while (done < len) {
    const double inPeriod = std::fmod(s, kPeriod);
    const double step = std::min(len - done, inPeriod < kOn ? kOn - inPeriod : kPeriod - inPeriod);
    if (inPeriod < kOn) cv::line(img, a + (b - a) * (done / len), a + (b - a) * ((done + step) / len), c, width, cv::LINE_AA);
    done += step;
    s += step;
  }
}

void drawMarker(cv::Mat& img, cv::Point2d p, Marker m, double size, const cv::Scalar& c) {
  const int s = static_cast<int>(std::round(size));
  switch (m) {
    case Marker::None: break;
    case Marker::Circle: cv::circle(img, p, s, c, cv::FILLED, cv::LINE_AA); break;
    case Marker::Cross:
      cv::line(img, p + cv::Point2d(-s, -s), p + cv::Point2d(s, s), c, 2, cv::LINE_AA);
      cv::line(img, p + cv::Point2d(-s, s), p + cv::Point2d(s, -s), c, 2, cv::LINE_AA);
      break;
    case Marker::Square: cv::rectangle(img, p + cv::Point2d(-s, -s), p + cv::Point2d(s, s), c, cv::FILLED); break;
    case Marker::Triangle: {
      std::vector<cv::Point> tri = {p + cv::Point2d(0, -s), p + cv::Point2d(-s, s), p + cv::Point2d(s, s)};
      cv::fillConvexPoly(img, tri, c, cv::LINE_AA);
      break;
    }
  }
}

/// The axes' data range: over finite values, bands and reference lines, with a margin, unless limits are set.
struct DataRange {
  double x0, x1, y0, y1;
};

DataRange dataRange(const Axes& ax) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : ax.series())
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x0 = std::min(x0, s.x[i]); x1 = std::max(x1, s.x[i]);
        y0 = std::min(y0, s.y[i]); y1 = std::max(y1, s.y[i]);
      }
  for (const auto& b : ax.bands()) { x0 = std::min(x0, b.x0); x1 = std::max(x1, b.x1); }
  for (const auto& r : ax.refLines()) {
    if (r.vertical) { x0 = std::min(x0, r.value); x1 = std::max(x1, r.value); }
    else { y0 = std::min(y0, r.value); y1 = std::max(y1, r.value); }
  }
  if (!std::isfinite(x0)) { x0 = 0; x1 = 1; }
  if (!std::isfinite(y0)) { y0 = 0; y1 = 1; }
  if (x1 - x0 < 1e-12) { x0 -= 0.5; x1 += 0.5; }
  if (y1 - y0 < 1e-12) { y0 -= 0.5; y1 += 0.5; }
  const double mx = 0.03 * (x1 - x0), my = 0.06 * (y1 - y0);
  x0 -= mx; x1 += mx; y0 -= my; y1 += my;
  if (ax.xLimits) std::tie(x0, x1) = *ax.xLimits;
  if (ax.yLimits) std::tie(y0, y1) = *ax.yLimits;
  return {x0, x1, y0, y1};
}

/// The y label, turned a quarter left, beside the plot area.
void drawYLabel(cv::Mat& img, const Axes& ax, const cv::Rect& cell, const cv::Rect& plot) {
  int base = 0;
  const cv::Size sz = cv::getTextSize(ax.yLabel, kFont, 0.45, 1, &base);
  cv::Mat label(sz.height + base + 4, sz.width + 4, CV_8UC3, kWhite);
  cv::putText(label, ax.yLabel, cv::Point(2, sz.height + 1), kFont, 0.45, kBlack, 1, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(label, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int x = cell.x + 4, y = plot.y + plot.height / 2 - rotated.rows / 2;
  if (y >= 0 && y + rotated.rows <= img.rows && x + rotated.cols <= img.cols)
    rotated.copyTo(img(cv::Rect(x, y, rotated.cols, rotated.rows)));
}

/// The legend box in the plot's top right corner: one row per labelled series, then per labelled band.
void drawLegend(cv::Mat& img, const Axes& ax, const cv::Rect& plot) {
  int n = 0, wmax = 0;
  for (const auto& s : ax.series())
    if (!s.label.empty()) {
      ++n;
      int base = 0;
      wmax = std::max(wmax, cv::getTextSize(s.label, kFont, 0.4, 1, &base).width);
    }
  for (const auto& b : ax.bands())
    if (!b.label.empty()) {
      ++n;
      int base = 0;
      wmax = std::max(wmax, cv::getTextSize(b.label, kFont, 0.4, 1, &base).width);
    }
  if (n > 0) {
    const cv::Rect box(plot.x + plot.width - wmax - 45, plot.y + 6, wmax + 38, 18 * n + 6);
    cv::rectangle(img, box, kWhite, cv::FILLED);
    cv::rectangle(img, box, cv::Scalar(180, 180, 180), 1);
    int row = 0;
    for (const auto& s : ax.series()) {
      if (s.label.empty()) continue;
      const int y = box.y + 14 + 18 * row++;
      const cv::Point2d a(box.x + 6, y - 4), b(box.x + 26, y - 4);
      if (s.lineWidth_px > 0) {
        if (s.dashed) dashedLine(img, a, b, bgr(s.colour), 2);
        else cv::line(img, a, b, bgr(s.colour), 2, cv::LINE_AA);
      }
      drawMarker(img, (a + b) * 0.5, s.marker, std::min(4.0, s.markerSize_px), bgr(s.colour));
      text(img, s.label, cv::Point(box.x + 32, y), 0.4, kBlack);
    }
    for (const auto& b : ax.bands()) {
      if (b.label.empty()) continue;
      const int y = box.y + 14 + 18 * row++;
      const cv::Rect swatch(box.x + 8, y - 11, 16, 12);
      cv::Mat area = img(swatch);
      cv::addWeighted(area, 1.0 - b.opacity, cv::Mat(area.size(), area.type(), bgr(b.colour)), b.opacity, 0.0, area);
      cv::rectangle(img, swatch, bgr(b.colour), 1);
      text(img, b.label, cv::Point(box.x + 32, y), 0.4, kBlack);
    }
  }
}

void drawAxes(cv::Mat& img, const Axes& ax, cv::Rect cell) {
  // Data range over finite values and reference lines.
  const DataRange range = dataRange(ax);
  double x0 = range.x0, x1 = range.x1, y0 = range.y0, y1 = range.y1;

  const int left = 70, right = 15, top = ax.title.empty() ? 15 : 35, bottom = 50;
  cv::Rect plot(cell.x + left, cell.y + top, cell.width - left - right, cell.height - top - bottom);
  if (plot.width < 20 || plot.height < 20) return;
  if (ax.equalAspect) {
    const double sx = plot.width / (x1 - x0), sy = plot.height / (y1 - y0);
    if (sx > sy) { const double c = (x0 + x1) / 2, h = plot.width / sy / 2; x0 = c - h; x1 = c + h; }
    else { const double c = (y0 + y1) / 2, h = plot.height / sx / 2; y0 = c - h; y1 = c + h; }
  }
  const auto px = [&](double x, double y) {
    return cv::Point2d(plot.x + (x - x0) / (x1 - x0) * plot.width, plot.y + plot.height - (y - y0) / (y1 - y0) * plot.height);
  };

  // Bands first, under the grid and the data.
  for (const auto& b : ax.bands()) {
    const double a = std::clamp(px(b.x0, y0).x, double(plot.x), double(plot.x + plot.width));
    const double e = std::clamp(px(b.x1, y0).x, double(plot.x), double(plot.x + plot.width));
    const cv::Rect r(static_cast<int>(std::round(a)), plot.y, static_cast<int>(std::round(e - a)), plot.height);
    if (r.width <= 0) continue;
    cv::Mat area = img(r);
    cv::addWeighted(area, 1.0 - b.opacity, cv::Mat(area.size(), area.type(), bgr(b.colour)), b.opacity, 0.0, area);
  }

  // Grid and ticks.
  const double xs = tickStep(x1 - x0, std::max(2, plot.width / 90)), ys = tickStep(y1 - y0, std::max(2, plot.height / 50));
  for (double x = std::ceil(x0 / xs) * xs; x <= x1 + 1e-12; x += xs) {
    const cv::Point2d p = px(x, y0);
    cv::line(img, cv::Point2d(p.x, plot.y), cv::Point2d(p.x, plot.y + plot.height), kGrid, 1);
    text(img, tickLabel(x, xs), cv::Point(static_cast<int>(p.x), plot.y + plot.height + 18), 0.4, kBlack, 1);
  }
  for (double y = std::ceil(y0 / ys) * ys; y <= y1 + 1e-12; y += ys) {
    const cv::Point2d p = px(x0, y);
    cv::line(img, cv::Point2d(plot.x, p.y), cv::Point2d(plot.x + plot.width, p.y), kGrid, 1);
    text(img, tickLabel(y, ys), cv::Point(plot.x - 6, static_cast<int>(p.y) + 4), 0.4, kBlack, 2);
  }
  cv::rectangle(img, plot, kBlack, 1);

  // Data, clipped to the plot area.
  cv::Mat roi = img(plot);
  const cv::Point2d off(plot.x, plot.y);
  for (const auto& r : ax.refLines()) {
    const cv::Point2d a = r.vertical ? px(r.value, y0) : px(x0, r.value);
    const cv::Point2d b = r.vertical ? px(r.value, y1) : px(x1, r.value);
    if (r.dashed) dashedLine(roi, a - off, b - off, bgr(r.colour), 1);
    else cv::line(roi, a - off, b - off, bgr(r.colour), 1, cv::LINE_AA);
    if (!r.label.empty())
      text(img, r.label, r.vertical ? cv::Point(static_cast<int>(a.x) + 3, plot.y + 12)
                                    : cv::Point(plot.x + 4, static_cast<int>(a.y) - 3), 0.38, bgr(r.colour));
  }
  for (const auto& s : ax.series()) {
    const cv::Scalar c = bgr(s.colour);
    double phase = 0.0;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      const cv::Point2d p = px(s.x[i], s.y[i]) - off;
      if (s.lineWidth_px > 0 && i > 0 && std::isfinite(s.x[i - 1]) && std::isfinite(s.y[i - 1])) {
        const cv::Point2d q = px(s.x[i - 1], s.y[i - 1]) - off;
        const int w = std::max(1, static_cast<int>(std::round(s.lineWidth_px)));
        if (s.dashed) dashedLine(roi, q, p, c, w, &phase);
        else cv::line(roi, q, p, c, w, cv::LINE_AA);
      }
      drawMarker(roi, p, s.marker, s.markerSize_px, c);
    }
  }

  // Labels and legend.
  if (!ax.title.empty()) text(img, ax.title, cv::Point(plot.x + plot.width / 2, cell.y + 22), 0.55, kBlack, 1);
  if (!ax.xLabel.empty()) text(img, ax.xLabel, cv::Point(plot.x + plot.width / 2, plot.y + plot.height + 40), 0.45, kBlack, 1);
  if (!ax.yLabel.empty()) drawYLabel(img, ax, cell, plot);
  if (ax.legend) drawLegend(img, ax, plot);
}

cv::Mat render(int width, int height, int rows, int cols, const std::string& title, const std::vector<Axes>& axes) {
  cv::Mat img(height, width, CV_8UC3, kWhite);
  const int top = title.empty() ? 0 : 34;
  if (!title.empty()) text(img, title, cv::Point(width / 2, 24), 0.65, kBlack, 1);
  const int cw = width / cols, ch = (height - top) / rows;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      drawAxes(img, axes[static_cast<std::size_t>(r * cols + c)], cv::Rect(c * cw, top + r * ch, cw, ch));
  return img;
}

}  // namespace

std::vector<unsigned char> Figure::encodePng() const {
  std::vector<unsigned char> png;
  cv::imencode(".png", render(width_px_, height_px_, rows_, cols_, title, axes_), png);
  return png;
}

void Figure::save(const std::string& path) const {
  bool ok = false;
  try {
    ok = cv::imwrite(path, render(width_px_, height_px_, rows_, cols_, title, axes_));
  } catch (const cv::Exception& e) {
    throw core::FileError(path, std::string("cannot write PNG: ") + e.what());
  }
  if (!ok) throw core::FileError(path, "cannot write PNG (is the folder there and writable?)");
}

}  // namespace srp::plot
