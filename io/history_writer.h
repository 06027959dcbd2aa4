// History writer system: a CSV file with one row per converged increment.
//
// Reads  the World (reactions, tool reactions, fibre state) and the increment's StepReport,
//        through column families; writes PATH.part row by row (each row whole and flushed) and
//        renames it to PATH on close(), so PATH exists only complete (interrupted runs included:
//        it then holds every increment that converged). Serial; the caller's thread.
//
// Columns come in families, each contributed by one system: a header list and a function that
// appends as many values per row. A system adds its columns by adding a family:
//
//   std::vector<HistoryColumns> columns = standardHistoryColumns(world);
//   columns.push_back({{"contact.zones", "contact.elements"},
//                      [](const World&, const StepReport& r, std::vector<double>& row) {
//                        row.push_back(r.contact.zones);
//                        row.push_back(r.contact.elements);
//                      }});
//   HistoryWriter history(dir + "/history.csv", std::move(columns));
//   ... history.append(world, report) after every converged increment ...
//   history.close();
//
// Column names must be unique across families; values are written as the shortest decimal that
// reads back exactly.
#pragma once

#include "engine/world.h"
#include "io/output_file.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fibra {

struct HistoryColumns {
  std::vector<std::string> names;
  // Appends names.size() values for the world's current (converged) state.
  std::function<void(const World&, const StepReport&, std::vector<double>& row)> values;
};

// time, step (1-based), increment (1-based within the step), load_factor (fraction of the
// step), iterations (Newton, last converged attempt), total_iterations (all attempts), cutbacks
// (failed attempts), sub_increments (converged attempts that make up the increment),
// smallest_increment (pseudo-time size of the smallest of them), residual (relative), wall_s
// (seconds of the increment).
HistoryColumns incrementColumns();
// Per boundary condition: reaction.G.fx .fy .fz (N) and .mx .my .mz (N mm, about
// output.moment_point), World::reaction: what the held DOFs exert on the fibres, balancing the
// loads. G is the group ("G#i" for boundary condition i when groups repeat).
HistoryColumns reactionColumns(const World& world);
// Per tool T: tool.T.fx .fy .fz, the force the fibres exert on it (N), and tool.T.ux .uy .uz,
// the displacement of its point (the scene's `point`) by its motion since t = 0 (mm).
HistoryColumns toolColumns(const World& world);
// With contact or tools: contact.zones, .elements, .tool_elements, .active, .sliding (counts),
// .max_penetration (mm), .max_penetration_ratio (of p_max), .detection_loops, .normal_loops,
// .restarts (loops A and B of the increment), .stabilisation (|stabilisation forces| / F_ref),
// .detections, .broadphase_rebuilds (detection passes of the increment's last attempt, and those
// that rebuilt the broadphase's candidate set), .candidate_pairs (of the last detection), ...,
// .normal_mixes (normal updates of loop B replaced by the Anderson-mixed normals, summed over
// loop A; contact `normal_acceleration`), .refined_zones (zones of the accepted set with
// Lobatto elements by the acceptance's refinement, ZoneStore::refined), .false_clearance (mm:
// the fibres' largest clearance near an element of the accepted set that pushes,
// systems/contact_queries.h falseForce; 0 when every pushing element's fibres touch).
HistoryColumns contactColumns(const World& world);
// When some step has damping: viscous_force, |the continuation's force on the free DOFs| / F_ref
// at the end of the increment (how far the state is from static equilibrium; 0 in steps
// without damping).
HistoryColumns continuationColumns(const World& world);
// The increment's linear solves, all attempts (core/report.h LinearReport):
// linear.factorisations, .solves, .fallbacks, .krylov_iterations (GMRES, summed), .krylov_max (of
// one solve), .krylov_failures. Not the symbolic analyses: a resumed run analyses again where
// the uninterrupted one re-used its analysis, and the history of both must be the same.
HistoryColumns linearColumns();
// Per probe P: probe.P.x .y .z, the position of its node (mm).
HistoryColumns probeColumns(const World& world);
// All of the above, in that order.
std::vector<HistoryColumns> standardHistoryColumns(const World& world);

class HistoryWriter {
 public:
  // Writes the header line, then `rows` (lines without their newline: the rows of a run this one
  // resumes); throws std::invalid_argument for repeated column names and std::runtime_error
  // when the file cannot be written.
  HistoryWriter(const std::string& path, std::vector<HistoryColumns> columns,
                const std::vector<std::string>& rows = {});
  ~HistoryWriter();  // closes, errors ignored

  void append(const World& world, const StepReport& report);  // one row, flushed
  void close();  // PATH.part -> PATH; later calls do nothing
  const std::vector<std::string>& header() const { return header_; }

 private:
  std::vector<HistoryColumns> columns_;
  std::vector<std::string> header_;
  std::unique_ptr<OutputFile> file_;
  std::vector<double> row_;
};

}  // namespace fibra
