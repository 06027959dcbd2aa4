#include "io/history_writer.h"

#include "systems/tool_geometry.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace fibra {
namespace {

void appendVec(std::vector<double>& row, const Vec3& v) {
  row.insert(row.end(), v.data(), v.data() + 3);
}

void addNames(std::vector<std::string>& names, const std::string& prefix,
              std::initializer_list<const char*> suffixes) {
  for (const char* s : suffixes) names.push_back(prefix + "." + s);
}

// Global node of each probe.
std::vector<Index> probeNodes(const World& world) {
  const FibreStore& fs = world.fibres();
  std::vector<Index> nodes;
  for (const ProbeDef& p : world.scene().output.probes) {
    const auto f = std::find(fs.name.begin(), fs.name.end(), p.fibre);
    if (f == fs.name.end())
      throw std::invalid_argument("probe '" + p.name + "': unknown fibre '" + p.fibre + "'");
    nodes.push_back(fs.firstNode[f - fs.name.begin()] + p.node);
  }
  return nodes;
}

}  // namespace

HistoryColumns incrementColumns() {
  return {{"time", "step", "increment", "load_factor", "iterations", "total_iterations", "cutbacks",
           "sub_increments", "smallest_increment", "predicted", "predictor_retries",
           "normal_retries", "damped_steps", "residual", "wall_s"},
          [](const World&, const StepReport& r, std::vector<double>& row) {
            row.insert(row.end(), {r.time, double(r.step + 1), double(r.increment), r.loadFactor,
                                   double(r.iterations), double(r.totalIterations),
                                   double(r.cutbacks), double(r.subIncrements),
                                   r.smallestIncrement, double(r.predicted),
                                   double(r.predictorRetries), double(r.normalRetries),
                                   double(r.dampedSteps), r.residual, r.timings.total});
          }};
}

HistoryColumns reactionColumns(const World& world) {
  const std::vector<BcDef>& bcs = world.scene().bcs;
  std::map<std::string, int> uses;
  for (const BcDef& b : bcs) ++uses[b.group];
  HistoryColumns c;
  for (size_t b = 0; b < bcs.size(); ++b) {
    std::string name = bcs[b].group;
    if (uses[name] > 1) name += '#' + std::to_string(b);
    addNames(c.names, "reaction." + name, {"fx", "fy", "fz", "mx", "my", "mz"});
  }
  const Index count = Index(bcs.size());
  c.values = [count](const World& w, const StepReport&, std::vector<double>& row) {
    for (Index b = 0; b < count; ++b) {
      const Reaction r = w.reaction(b);
      appendVec(row, r.force);
      appendVec(row, r.moment);
    }
  };
  return c;
}

HistoryColumns toolColumns(const World& world) {
  HistoryColumns c;
  for (const ToolDef& t : world.scene().tools)
    addNames(c.names, "tool." + t.name, {"fx", "fy", "fz", "ux", "uy", "uz"});
  const Index count = Index(world.scene().tools.size());
  c.values = [count](const World& w, const StepReport& r, std::vector<double>& row) {
    const ToolStore& tools = w.tools();
    for (Index t = 0; t < count; ++t) {
      appendVec(row, w.toolReaction(t));
      const Vec3& point = tools.point[t];
      appendVec(row, toolMotion(tools, t, r.time)(point) - point);
    }
  };
  return c;
}

HistoryColumns contactColumns(const World& world) {
  const SceneDef& s = world.scene();
  if (!s.contact.enabled && s.tools.empty())
    return {{}, [](const World&, const StepReport&, std::vector<double>&) {}};
  return {{"contact.zones", "contact.elements", "contact.tool_elements", "contact.active",
           "contact.sliding", "contact.max_penetration", "contact.max_penetration_ratio",
           "contact.detection_loops", "contact.normal_loops", "contact.restarts",
           "contact.stabilisation", "contact.detections", "contact.broadphase_rebuilds",
           "contact.candidate_pairs", "contact.loop_a_capped", "contact.max_overlap",
           "contact.redetect_zone_changes", "contact.redetect_gap_change",
           "contact.redetect_particle_shift", "contact.consistency_passes",
           "contact.friction_held", "contact.friction_excess", "contact.normal_mixes",
           "contact.refined_zones", "contact.false_clearance"},
          [](const World&, const StepReport& r, std::vector<double>& row) {
            const ContactReport& c = r.contact;
            row.insert(row.end(), {double(c.zones), double(c.elements), double(c.toolElements),
                                   double(c.active), double(c.sliding), c.maxPenetration,
                                   c.maxPenetrationRatio, double(c.detectionLoops),
                                   double(c.normalLoops), double(c.restarts), c.stabilisation,
                                   double(c.detections), double(c.broadphaseRebuilds),
                                   double(c.candidatePairs), double(c.loopCapped),
                                   c.maxOverlap, double(c.redetectZoneChanges),
                                   c.redetectGapChange, c.redetectParticleShift,
                                   double(c.consistencyPasses), double(c.frictionHeld),
                                   c.frictionExcess, double(c.normalMixes),
                                   double(c.refinedZones), c.falseClearance});
          }};
}

HistoryColumns continuationColumns(const World& world) {
  const std::vector<StepDef>& steps = world.scene().steps;
  if (std::none_of(steps.begin(), steps.end(), [](const StepDef& s) { return s.damping > 0; }))
    return {{}, [](const World&, const StepReport&, std::vector<double>&) {}};
  return {{"viscous_force"}, [](const World&, const StepReport& r, std::vector<double>& row) {
            row.push_back(r.viscousForce);
          }};
}

// The energy balance since t = 0 (core/report.h EnergyBalance), N mm.
HistoryColumns energyColumns() {
  return {{"energy.strain", "energy.external", "energy.supports", "energy.contact_normal",
           "energy.friction", "energy.tools", "energy.stabilisation", "energy.error"},
          [](const World&, const StepReport& r, std::vector<double>& row) {
            const EnergyBalance& e = r.energy;
            row.insert(row.end(), {e.strain, e.external, e.supports, e.contactNormal, e.friction,
                                   e.tools, e.stabilisation, e.error()});
          }};
}

HistoryColumns linearColumns() {
  return {{"linear.factorisations", "linear.solves", "linear.fallbacks",
           "linear.krylov_iterations", "linear.krylov_max", "linear.krylov_failures"},
          [](const World&, const StepReport& r, std::vector<double>& row) {
            const LinearReport& l = r.linear;
            row.insert(row.end(), {double(l.factorisations), double(l.solves), double(l.fallbacks),
                                   double(l.krylovIterations), double(l.maxKrylovIterations),
                                   double(l.krylovFailures)});
          }};
}

HistoryColumns probeColumns(const World& world) {
  HistoryColumns c;
  for (const ProbeDef& p : world.scene().output.probes)
    addNames(c.names, "probe." + p.name, {"x", "y", "z"});
  c.values = [nodes = probeNodes(world)](const World& w, const StepReport&,
                                         std::vector<double>& row) {
    for (Index n : nodes) appendVec(row, x0Of(w.fibres().q, n));
  };
  return c;
}

std::vector<HistoryColumns> standardHistoryColumns(const World& world) {
  return {incrementColumns(),    reactionColumns(world),     toolColumns(world),
          contactColumns(world), continuationColumns(world), energyColumns(),
          linearColumns(),       probeColumns(world)};
}

HistoryWriter::HistoryWriter(const std::string& path, std::vector<HistoryColumns> columns,
                             const std::vector<std::string>& rows)
    : columns_(std::move(columns)) {
  std::set<std::string> seen;
  for (const HistoryColumns& family : columns_)
    for (const std::string& name : family.names) {
      if (!seen.insert(name).second)
        throw std::invalid_argument("history column '" + name + "' repeated");
      header_.push_back(name);
    }
  file_ = std::make_unique<OutputFile>(path);
  std::string line;
  for (const std::string& name : header_) line += (line.empty() ? "" : ",") + name;
  file_->stream() << line << '\n';
  for (const std::string& row : rows) file_->stream() << row << '\n';
  file_->flush();
}

HistoryWriter::~HistoryWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Destructors run on error paths, where the first error is the one to report.
  }
}

void HistoryWriter::append(const World& world, const StepReport& report) {
  if (file_->committed()) throw std::logic_error("history appended after close()");
  row_.clear();
  for (size_t k = 0; k < columns_.size(); ++k) {
    const size_t before = row_.size();
    columns_[k].values(world, report, row_);
    if (row_.size() - before != columns_[k].names.size())
      throw std::logic_error("history column family " + std::to_string(k) + " gave " +
                             std::to_string(row_.size() - before) + " values for " +
                             std::to_string(columns_[k].names.size()) + " columns");
  }
  std::string line;
  for (size_t i = 0; i < row_.size(); ++i) {
    if (i) line += ',';
    appendNumber(line, row_[i]);
  }
  file_->stream() << line << '\n';
  file_->flush();
}

void HistoryWriter::close() {
  if (!file_->committed()) file_->commit();
}

}  // namespace fibra
