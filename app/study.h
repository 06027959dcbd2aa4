// fibra study: speed against error. Runs variants of one scene that differ in one field (a
// discretisation or solver knob), measures each variant's wall time and Newton iterations, and
// its error against a reference variant on chosen history columns (docs/PLOTS.md, "Speed
// against error: fibra study").
//
//   fibra study SCENE --vary FIELD=V1,V2,... --observe COLUMN[,COLUMN...] --out DIR
//               [--reference V] [--threads N]
//
// FIELD is a path in the scene's JSON ("fibres[0].elements", "steps[0].increments",
// "contact.max_penetration", "solver.strategy"); each value replaces it (a number when it reads
// as a JSON number, true/false as booleans, a string otherwise). Every variant is loaded,
// validated and its World built before anything runs or is written (bad input: exit 2). Each
// runs in DIR/FIELD=VALUE/ (fibra run's files); DIR/study.csv has one row per variant, and
// DIR/study.png with its script DIR/study.gp plots the error against wall time and iterations.
//
// Returns the exit status: 0 done (a failed variant other than the reference is a warning);
// 1 the reference failed, gnuplot missing or failing, or output not written; 2 bad input (no
// such field, a value the scene refuses, an unknown column, no reference for a categorical
// knob). Bad usage (unknown option, missing value) throws std::invalid_argument, which the
// program reports with its usage line (exit 2).
#pragma once

namespace fibra::study {

int study(int argc, char** argv);

}  // namespace fibra::study
