#include "evaluator/shape_geometry.hpp"

#include "frontend/diagnostics.hpp"
#include "symbolic/geometry.hpp"
#include "symbolic/mechanism.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::evaluator {

namespace {

class Builder {
 public:
  Builder(const ir::ModelIr& model, const std::map<std::string, std::string>& set)
      : model_(model), params_(model, set), mechanism_(symbolic::make_mechanism(model, params_)) {}

  // The index of the point at `at`, added on first use: an element's end at a body's centre or at another
  // element's end is that point, and the outputs measuring one place share its sensor point; every body has its own.
  int point(const ir::Attachment& at, ShapePoint::Kind kind, const std::string& label, const ir::SourceLoc& loc) {
    if (model_.is_ground(at.frame)) kind = ShapePoint::Kind::Ground;
    const Eigen::Vector3d position = value(symbolic::to_column(at.point, params_), loc);
    const auto same_kind = [&](ShapePoint::Kind there) {
      if (kind == ShapePoint::Kind::Body) return false;
      if (kind == ShapePoint::Kind::Sensor) return there == ShapePoint::Kind::Sensor;
      return there != ShapePoint::Kind::Sensor;
    };
    for (std::size_t k = 0; k < geometry_.points.size(); ++k)
      if (frames_[k] == at.frame && geometry_.points[k].position == position && same_kind(geometry_.points[k].kind))
        return static_cast<int>(k);
    geometry_.points.push_back({kind, label, position});
    frames_.push_back(at.frame);
    const std::array<symbolic::Row, 3> rows = symbolic::displacement_rows(mechanism_, at);
    motion_.emplace_back();
    for (const symbolic::Row& row : rows) {
      Eigen::RowVectorXd r(mechanism_.coordinate_count);
      for (int c = 0; c < mechanism_.coordinate_count; ++c) r[c] = number(row[static_cast<std::size_t>(c)], loc);
      motion_.back().push_back(r);
    }
    return static_cast<int>(geometry_.points.size()) - 1;
  }

  Eigen::Vector3d direction(const ir::Direction& d) {
    return value(symbolic::unit_direction(d, params_), d.loc);
  }

  ShapeGeometry take() {
    geometry_.motion.resize(3 * static_cast<Eigen::Index>(motion_.size()), mechanism_.coordinate_count);
    for (std::size_t k = 0; k < motion_.size(); ++k)
      for (std::size_t a = 0; a < 3; ++a) geometry_.motion.row(static_cast<Eigen::Index>(3 * k + a)) = motion_[k][a];
    return std::move(geometry_);
  }

  ShapeGeometry& geometry() { return geometry_; }

 private:
  double number(const GiNaC::ex& e, const ir::SourceLoc& loc) const {
    const GiNaC::ex v = e.subs(params_.values()).evalf();
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
      throw frontend::ModelError(model_.file, loc, "this point is not a number at the parameter values");
    return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
  }
  Eigen::Vector3d value(const GiNaC::matrix& column, const ir::SourceLoc& loc) const {
    return {number(column(0, 0), loc), number(column(1, 0), loc), number(column(2, 0), loc)};
  }

  const ir::ModelIr& model_;
  symbolic::ParameterTable params_;
  symbolic::Mechanism mechanism_;
  ShapeGeometry geometry_;
  std::vector<std::string> frames_;                         // per point
  std::vector<std::vector<Eigen::RowVectorXd>> motion_;     // per point, its x, y, z rows
};

}  // namespace

ShapeGeometry shape_geometry(const ir::ModelIr& model, const std::map<std::string, std::string>& set) {
  Builder b(model, set);
  for (const ir::Body& body : model.bodies) {
    ir::Attachment centre;
    centre.frame = body.name;
    centre.point = body.position;
    b.point(centre, ShapePoint::Kind::Body, body.name, body.loc);
  }
  for (const ir::Element& e : model.elements) {
    const int from = b.point(e.a, ShapePoint::Kind::Attachment, "", e.a.loc.line ? e.a.loc : e.loc);
    const int to = b.point(e.b, ShapePoint::Kind::Attachment, "", e.b.loc.line ? e.b.loc : e.loc);
    if (from != to) b.geometry().lines.emplace_back(from, to);
  }
  for (const ir::Output& out : model.outputs) {
    const int at = b.point(out.at, ShapePoint::Kind::Sensor, out.name, out.loc);
    b.geometry().sensors.push_back({out.name, at, b.direction(out.direction)});
  }
  return b.take();
}

}  // namespace mbgen::evaluator
