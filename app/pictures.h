// fibra plot and fibra section: the command-line shells over io/plot.h and io/section_cut.h.
//
//   fibra plot RUN_DIR --x COLUMN --y COLUMN[,COLUMN...] [--out FILE.png] [--title T]
//   fibra section RUN_DIR [--plane AXIS[=VALUE]] [--frame N[,N...]|last] [--out FILE.png]
//                 [--title T]
//
// Both return the exit status: 0 drawn, 1 gnuplot missing or failing, 2 bad input (no such run,
// unknown column, a plane that cuts no fibre). Bad usage (unknown option, missing value) throws
// std::invalid_argument, which the program reports with its usage line (exit 2).
#pragma once

namespace fibra::pictures {

int plot(int argc, char** argv);
int section(int argc, char** argv);

}  // namespace fibra::pictures
