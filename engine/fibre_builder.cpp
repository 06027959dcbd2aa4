#include "engine/fibre_builder.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace fibra {
namespace {

// A unit vector normal to t: the hint projected, or the coordinate axis least aligned with t.
Vec3 normalTo(const Vec3& t, const Vec3& hint) {
  Vec3 d = hint;
  if (!d.allFinite() || (d - d.dot(t) * t).norm() < 1e-8 * d.norm()) {
    Eigen::Index i;
    t.cwiseAbs().minCoeff(&i);
    d = Vec3::Unit(i);
  }
  return (d - d.dot(t) * t).normalized();
}

// Minimal rotation carrying unit a onto unit b, applied to v (parallel transport).
Vec3 transport(const Vec3& a, const Vec3& b, const Vec3& v) {
  return Eigen::Quaterniond::FromTwoVectors(a, b) * v;
}

struct Frame {
  Vec3 x, t, g1;
};

// Helix frames: phi = phase + sigma s / c, c = sqrt(r^2 + (p / 2 pi)^2).
Frame helixFrame(const GeometryDef& g, double s) {
  const Vec3 a = g.axis.normalized();
  const Vec3 e1 = normalTo(a, Vec3::Constant(std::nan(""))), e2 = a.cross(e1);
  const double k = g.pitch / (2 * std::numbers::pi);
  const double c = std::hypot(g.helixRadius, k), sigma = g.turns < 0 ? -1 : 1;
  const double phi = g.phase + sigma * s / c;
  const Vec3 er = std::cos(phi) * e1 + std::sin(phi) * e2;
  const Vec3 ep = -std::sin(phi) * e1 + std::cos(phi) * e2;
  return {g.origin + g.helixRadius * er + k * (s / c) * a,
          (g.helixRadius * sigma * ep + k * a) / c, er};
}

// Polyline: position and segment tangent at arc length s; at a vertex, the mean tangent.
Frame polylineFrame(const std::vector<Vec3>& p, double s) {
  double acc = 0;
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const double l = (p[i + 1] - p[i]).norm();
    const Vec3 t = (p[i + 1] - p[i]) / l;
    if (s <= acc + l * (1 + 1e-12) || i + 2 == p.size()) {
      const double u = std::clamp((s - acc) / l, 0.0, 1.0);
      Vec3 tt = t;
      if (u > 1 - 1e-12 && i + 2 < p.size()) tt = (t + (p[i + 2] - p[i + 1]).normalized()).normalized();
      if (u < 1e-12 && i > 0) tt = (t + (p[i] - p[i - 1]).normalized()).normalized();
      return {p[i] + u * (p[i + 1] - p[i]), tt, Vec3::Zero()};
    }
    acc += l;
  }
  return {p.back(), Vec3::UnitX(), Vec3::Zero()};
}

}  // namespace

double geometryLength(const GeometryDef& g) {
  if (g.kind == GeometryKind::Helix)
    return std::abs(g.turns) * 2 * std::numbers::pi *
           std::hypot(g.helixRadius, g.pitch / (2 * std::numbers::pi));
  double L = 0;
  for (size_t i = 0; i + 1 < g.points.size(); ++i) L += (g.points[i + 1] - g.points[i]).norm();
  return L;
}

void addFibre(FibreStore& fs, const FibreDef& def, Index material, const std::string& path) {
  const GeometryDef& g = def.geometry;
  const double L = geometryLength(g);
  if (!(L > 0) || !std::isfinite(L))
    throw SceneError(path + ".geometry: zero or undefined length");
  if (g.kind != GeometryKind::Helix)
    for (size_t i = 0; i + 1 < g.points.size(); ++i)
      if (!((g.points[i + 1] - g.points[i]).norm() > 0))
        throw SceneError(path + ".geometry.points[" + std::to_string(i + 1) +
                         "]: repeats the previous point");
  if (g.kind == GeometryKind::Helix && !(g.axis.norm() > 0))
    throw SceneError(path + ".geometry.axis: zero vector");

  const Index f = fs.fibres();
  const Index ne = def.elements, nn = def.order * ne + 1;
  const Index n0 = fs.nodes(), e0 = fs.elements();
  fs.name.push_back(def.name);
  fs.firstNode.push_back(n0);
  fs.nodeCount.push_back(nn);
  fs.firstElement.push_back(e0);
  fs.elementCount.push_back(ne);
  fs.order.push_back(def.order);
  fs.radius.push_back(def.radius);
  fs.length.push_back(L);
  fs.material.push_back(material);

  fs.q.conservativeResize(kNodeDofs * (n0 + nn));
  fs.qRef.conservativeResize(kNodeDofs * (n0 + nn));
  Vec3 tPrev = Vec3::Zero(), g1Prev = Vec3::Zero();
  for (Index i = 0; i < nn; ++i) {
    const double s = L * i / (nn - 1);
    Frame fr = g.kind == GeometryKind::Helix ? helixFrame(g, s) : polylineFrame(g.points, s);
    fr.t.normalize();
    if (g.kind != GeometryKind::Helix)
      fr.g1 = i == 0 ? normalTo(fr.t, g.director) : normalTo(fr.t, transport(tPrev, fr.t, g1Prev));
    tPrev = fr.t;
    g1Prev = fr.g1;
    const Index n = n0 + i;
    fs.nodeFibre.push_back(f);
    fs.nodeS.push_back(s);
    x0Of(fs.qRef, n) = fr.x;
    g1Of(fs.qRef, n) = fr.g1;
    g2Of(fs.qRef, n) = fr.t.cross(fr.g1);
  }
  fs.q.tail(kNodeDofs * nn) = fs.qRef.tail(kNodeDofs * nn);
  for (Index i = 0; i < ne; ++i) {
    fs.elementFibre.push_back(f);
    fs.elementFirstNode.push_back(n0 + def.order * i);
  }
}

}  // namespace fibra
