// What the fibra program prints on stderr while it runs: a header with the problem's size, one
// line per converged increment (or per Newton iteration with --verbose), and a closing summary.
// Numbers are printed with %g (six significant digits) unless a column needs exponents.
#pragma once

#include "engine/world.h"

#include <string>

namespace fibra::terminal {

enum class Verbosity { Quiet, Normal, Verbose };  // errors and summary; + increments; + iterations

// Problem size and derived parameters: fibres, nodes, elements, DOFs, steps and increments,
// contact (the section's resolved p_max, mu, angles, loops, self-contact separation; the laws:
// penalty bounds, initial penalty, p_reg, g_T,max, friction tangent, element placement; the
// fibres' contact classes and each contact.pairs rule's mu, p_max and penalty bounds; the steps
// with forced normals), tools, threads. Each line starts with "  " after a first line
// "fibra VERSION: SCENE".
std::string describeProblem(const World& world, const std::string& scene, int threads);

// The start warnings of describeProblem alone (a tool placed inside the fibres, a first forced
// step's allowance or spread), for --quiet, which prints no description.
std::string startWarnings(const World& world);

// What a run's terminal has explained once already (a mark that recurs gets its note once).
struct Explained {
  bool loopCapped = false;  // "loop A capped"
  bool normalChanges = false;  // contact normal_update "auto": the rules of its changes
};

// The increment's changes of how the fibre normals enter Newton (contact normal_update "auto",
// StepReport::normalChanges), in order, and what the step's next attempts use (`stepEnds`: none
// follow; a failed increment: none at all), as a "normals:" line; the rules once per run.
void printNormalChanges(const StepReport& r, bool stepEnds, Explained& explained);

void printIteration(const Progress& p);
void printIncrement(const StepReport& r, const SceneDef& scene, Verbosity v, Explained& explained);

}  // namespace fibra::terminal
