// Mode shapes as SVG text: three orthographic views of a model's points and elements, undeformed and deformed.
// Written directly rather than through gnuplot: the pictures are small and many, need equal scales across views,
// and come out the same bytes on every machine (numbers with two decimals).
#include "mbgen/report/mode_shape_svg.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

constexpr double kPanel = 240;     // each view's square, px
constexpr double kPad = 18;        // inside a view, around what it shows
constexpr double kMargin = 10;     // around and between the views
constexpr double kTitle = 26;      // the title line
constexpr double kViewLabel = 18;  // the view's name under it
constexpr double kLegendLine = 15;
const char* const kRestColour = "#c8c8c8";

// The horizontal and vertical global axes of each view.
constexpr int kViews[3][2] = {{0, 1}, {0, 2}, {1, 2}};
const char* const kViewNames[3] = {"x-y", "x-z", "y-z"};

std::string px(double v) {
  std::string s = detail::format("%.2f", v);
  return s == "-0.00" ? "0.00" : s;
}

std::string escaped(const std::string& text) {
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

bool draws(const ShapeLayer& layer, std::size_t k) { return layer.points.empty() || layer.points[k]; }

// Where the picture's drawing of one view puts a global point: the view's two axes, scaled, centred.
struct View {
  int h = 0, v = 1;
  double left = 0, top = 0;  // the panel's corner in the SVG
  double ch = 0, cv = 0;     // the global coordinates at the panel's centre
  double scale = 1;          // px per unit length
  double x(const Eigen::Vector3d& p) const { return left + kPanel / 2 + (p[h] - ch) * scale; }
  double y(const Eigen::Vector3d& p) const { return top + kPanel / 2 - (p[v] - cv) * scale; }
};

void point_mark(std::ostringstream& svg, const View& view, const ShapePoint::Kind kind, const Eigen::Vector3d& p,
                const std::string& colour, double size = 1) {
  const double x = view.x(p), y = view.y(p);
  switch (kind) {
    case ShapePoint::Kind::Body:
      svg << "<circle cx=\"" << px(x) << "\" cy=\"" << px(y) << "\" r=\"" << px(4 * size) << "\" fill=\"" << colour
          << "\"/>\n";
      break;
    case ShapePoint::Kind::Sensor:
      svg << "<rect x=\"" << px(x - 3.5 * size) << "\" y=\"" << px(y - 3.5 * size) << "\" width=\"" << px(7 * size)
          << "\" height=\"" << px(7 * size) << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\"/>\n";
      break;
    case ShapePoint::Kind::Attachment:
      svg << "<circle cx=\"" << px(x) << "\" cy=\"" << px(y) << "\" r=\"" << px(2 * size) << "\" fill=\"" << colour
          << "\"/>\n";
      break;
    case ShapePoint::Kind::Ground: break;  // anchors are drawn once, at rest
  }
}

// A ground point: a short bar under the point with hatching below it.
void ground_mark(std::ostringstream& svg, const View& view, const Eigen::Vector3d& p) {
  const double x = view.x(p), y = view.y(p);
  svg << "<path d=\"M" << px(x - 7) << " " << px(y + 4) << " H" << px(x + 7);
  for (int k = 0; k < 4; ++k)
    svg << " M" << px(x - 6 + 4 * k) << " " << px(y + 4) << " l-4 5";
  svg << " M" << px(x) << " " << px(y) << " V" << px(y + 4) << "\" stroke=\"#777777\" stroke-width=\"1\" "
      << "fill=\"none\"/>\n";
}

void line(std::ostringstream& svg, const View& view, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
          const std::string& colour, double width, const char* dash = nullptr) {
  svg << "<line x1=\"" << px(view.x(a)) << "\" y1=\"" << px(view.y(a)) << "\" x2=\"" << px(view.x(b)) << "\" y2=\""
      << px(view.y(b)) << "\" stroke=\"" << colour << "\" stroke-width=\"" << width << "\"";
  if (dash) svg << " stroke-dasharray=\"" << dash << "\"";
  svg << "/>\n";
}

// One view: the undeformed geometry, then each layer's deformed one.
void draw_view(std::ostringstream& svg, const View& view, int index, const ShapeGeometry& g,
               const std::vector<ShapeLayer>& layers, const std::vector<Eigen::Matrix3Xd>& moved) {
  svg << "<g clip-path=\"url(#view" << index << ")\">\n";
  for (const auto& [a, b] : g.lines)
    line(svg, view, g.points[static_cast<std::size_t>(a)].position, g.points[static_cast<std::size_t>(b)].position,
         kRestColour, 1.5);
  for (const ShapePoint& p : g.points) {
    if (p.kind == ShapePoint::Kind::Ground) ground_mark(svg, view, p.position);
    point_mark(svg, view, p.kind, p.position, kRestColour);
  }
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const ShapeLayer& layer = layers[l];
    const Eigen::Matrix3Xd& at = moved[l];
    if (layer.lines)
      for (const auto& [a, b] : g.lines)
        if (draws(layer, static_cast<std::size_t>(a)) && draws(layer, static_cast<std::size_t>(b)))
          line(svg, view, at.col(a), at.col(b), layer.colour, 1.5);
    for (std::size_t k = 0; k < g.points.size(); ++k) {
      if (!draws(layer, k)) continue;
      const Eigen::Index ki = static_cast<Eigen::Index>(k);
      if (layer.arrows) line(svg, view, g.points[k].position, at.col(ki), layer.colour, 1, "3 2");
      point_mark(svg, view, g.points[k].kind, at.col(ki), layer.colour, layer.marker);
    }
  }
  // The bodies' names beside their marks: where the first layer that draws the body with its elements moved it (so
  // that bodies which rest at one place are told apart), else at rest; names at one place stacked downwards.
  std::vector<std::pair<std::string, std::string>> named;  // (x, y) as written
  for (std::size_t k = 0; k < g.points.size(); ++k) {
    const ShapePoint& p = g.points[k];
    if (p.kind != ShapePoint::Kind::Body || p.label.empty()) continue;
    Eigen::Vector3d where = p.position;
    for (std::size_t l = 0; l < layers.size(); ++l)
      if (layers[l].lines && draws(layers[l], k)) {
        where = moved[l].col(static_cast<Eigen::Index>(k));
        break;
      }
    const std::pair<std::string, std::string> at{px(view.x(where)), px(view.y(where))};
    const double below = 10.0 * static_cast<double>(std::count(named.begin(), named.end(), at));
    named.push_back(at);
    const bool right_half = view.x(where) > view.left + kPanel / 2;  // named to the left there, not cut off
    svg << "<text x=\"" << px(view.x(where) + (right_half ? -5 : 5)) << "\" y=\"" << px(view.y(where) - 5 + below)
        << "\" font-size=\"9\" fill=\"#777777\"" << (right_half ? " text-anchor=\"end\"" : "") << ">"
        << escaped(p.label) << "</text>\n";
  }
  svg << "</g>\n";
}

}  // namespace

Eigen::Matrix3Xd point_displacements(const ShapeGeometry& geometry, const Eigen::VectorXcd& shape) {
  const Eigen::Index n = geometry.motion.cols(), points = static_cast<Eigen::Index>(geometry.points.size());
  Eigen::VectorXcd q = Eigen::VectorXcd::Zero(n);  // the body coordinates; a shorter shape moves the rest none
  q.head(std::min(n, shape.size())) = shape.head(std::min(n, shape.size()));
  const Eigen::VectorXcd d = geometry.motion.cast<std::complex<double>>() * q;
  Eigen::Matrix3Xcd by_point(3, points);
  for (Eigen::Index k = 0; k < points; ++k) by_point.col(k) = d.segment(3 * k, 3);
  return real_at_peak(by_point, by_point);
}

Eigen::Matrix3Xcd sensor_translations(const ShapeGeometry& geometry, const SensorShape& shape,
                                      std::vector<bool>& measured) {
  Eigen::Matrix3Xcd d = Eigen::Matrix3Xcd::Zero(3, static_cast<Eigen::Index>(geometry.points.size()));
  measured.assign(geometry.points.size(), false);
  for (std::size_t s = 0; s < shape.sensor.size(); ++s) {
    const int k = shape.sensor[s];
    const std::complex<double> v = shape.value[static_cast<Eigen::Index>(s)];
    if (k < 0 || k >= static_cast<int>(geometry.sensors.size()) || !std::isfinite(v.real()) ||
        !std::isfinite(v.imag()))
      continue;
    const ShapeSensor& sensor = geometry.sensors[static_cast<std::size_t>(k)];
    d.col(sensor.point) += v * sensor.direction.cast<std::complex<double>>();
    measured[static_cast<std::size_t>(sensor.point)] = true;
  }
  return d;
}

Eigen::Matrix3Xd real_at_peak(const Eigen::Matrix3Xcd& translations, const Eigen::Matrix3Xcd& reference) {
  double largest = 0;
  std::complex<double> peak(1, 0);
  for (Eigen::Index k = 0; k < reference.cols(); ++k)
    for (Eigen::Index a = 0; a < 3; ++a)
      if (std::abs(reference(a, k)) > largest) {
        largest = std::abs(reference(a, k));
        peak = reference(a, k);
      }
  const std::complex<double> turn = largest > 0 ? std::conj(peak) / largest : std::complex<double>(1, 0);
  return (translations * turn).real();
}

std::string mode_shape_svg(const ShapeGeometry& g, const std::vector<ShapeLayer>& layers, const std::string& title) {
  // The model's size, and the one factor that draws the largest displacement as kShapeFraction of it.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const ShapePoint& p : g.points) {
    lo = lo.cwiseMin(p.position);
    hi = hi.cwiseMax(p.position);
  }
  double size = g.points.empty() ? 0.0 : (hi - lo).maxCoeff();
  if (!(size > 0) || !std::isfinite(size)) size = 1;
  double largest = 0;
  for (const ShapeLayer& layer : layers)
    for (std::size_t k = 0; k < g.points.size(); ++k)
      if (draws(layer, k)) largest = std::max(largest, layer.displacement.col(static_cast<Eigen::Index>(k)).norm());
  const double factor = largest > 0 && std::isfinite(largest) ? kShapeFraction * size / largest : 0.0;
  std::vector<Eigen::Matrix3Xd> moved;
  for (const ShapeLayer& layer : layers) {
    Eigen::Matrix3Xd at(3, static_cast<Eigen::Index>(g.points.size()));
    for (std::size_t k = 0; k < g.points.size(); ++k) {
      const Eigen::Index ki = static_cast<Eigen::Index>(k);
      at.col(ki) = g.points[k].position + (draws(layer, k) ? factor * layer.displacement.col(ki)
                                                           : Eigen::Vector3d::Zero().eval());
      lo = lo.cwiseMin(at.col(ki));
      hi = hi.cwiseMax(at.col(ki));
    }
    moved.push_back(std::move(at));
  }
  // One scale for the three views: the largest extent of everything drawn fills a panel.
  const double extent = g.points.empty() ? 0.0 : (hi - lo).maxCoeff();
  const double scale = extent > 0 && std::isfinite(extent) ? (kPanel - 2 * kPad) / extent : 1.0;

  std::size_t legends = 0;
  for (const ShapeLayer& layer : layers) legends += layer.legend.empty() ? 0 : 1;
  ++legends;  // the scale
  const double width = 3 * kPanel + 4 * kMargin;
  const double height = kTitle + kPanel + kViewLabel + kLegendLine * static_cast<double>(legends) + kMargin;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << px(width) << "\" height=\"" << px(height)
      << "\" viewBox=\"0 0 " << px(width) << " " << px(height) << "\" font-family=\"sans-serif\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << px(kMargin) << "\" y=\"18\" font-size=\"13\">" << escaped(title) << "</text>\n<defs>\n";
  View views[3];
  for (int v = 0; v < 3; ++v) {
    View& view = views[v];
    view.h = kViews[v][0];
    view.v = kViews[v][1];
    view.left = kMargin + v * (kPanel + kMargin);
    view.top = kTitle;
    view.ch = g.points.empty() ? 0.0 : (lo[view.h] + hi[view.h]) / 2;
    view.cv = g.points.empty() ? 0.0 : (lo[view.v] + hi[view.v]) / 2;
    view.scale = scale;
    svg << "<clipPath id=\"view" << v << "\"><rect x=\"" << px(view.left) << "\" y=\"" << px(view.top)
        << "\" width=\"" << px(kPanel) << "\" height=\"" << px(kPanel) << "\"/></clipPath>\n";
  }
  svg << "</defs>\n";
  for (int v = 0; v < 3; ++v) {
    const View& view = views[v];
    svg << "<rect x=\"" << px(view.left) << "\" y=\"" << px(view.top) << "\" width=\"" << px(kPanel)
        << "\" height=\"" << px(kPanel) << "\" fill=\"none\" stroke=\"#dddddd\"/>\n";
    draw_view(svg, view, v, g, layers, moved);
    const char* axes = kViewNames[v];
    svg << "<text x=\"" << px(view.left + kPanel / 2) << "\" y=\"" << px(view.top + kPanel + 14)
        << "\" font-size=\"11\" text-anchor=\"middle\" fill=\"#555555\">" << axes << " (" << axes[0]
        << " to the right, " << axes[2] << " up)</text>\n";
  }
  double y = kTitle + kPanel + kViewLabel + 11;
  for (const ShapeLayer& layer : layers) {
    if (layer.legend.empty()) continue;
    svg << "<rect x=\"" << px(kMargin) << "\" y=\"" << px(y - 8) << "\" width=\"14\" height=\"3\" fill=\""
        << layer.colour << "\"/><text x=\"" << px(kMargin + 20) << "\" y=\"" << px(y) << "\" font-size=\"11\">"
        << escaped(layer.legend) << "</text>\n";
    y += kLegendLine;
  }
  svg << "<text x=\"" << px(kMargin) << "\" y=\"" << px(y) << "\" font-size=\"11\" fill=\"#555555\">";
  if (factor > 0)
    svg << "grey: at rest; the largest displacement drawn as " << detail::format("%.0f", 100 * kShapeFraction)
        << " % of the model's size";
  else
    svg << "The drawn points do not move in this mode (e.g. a rotation about an axis through them).";
  svg << "</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

std::string mode_title(const std::string& name, double f_hz, double zeta) {
  return name + detail::format(": %.6g Hz, zeta %.4g %%", f_hz, 100 * zeta);
}

std::string model_mode_svg(const ShapeGeometry& geometry, const std::string& title, const Eigen::VectorXcd& shape) {
  ShapeLayer layer;
  layer.displacement = point_displacements(geometry, shape);
  return mode_shape_svg(geometry, {layer}, title);
}

}  // namespace mbgen
