#include "io/plot.h"

#include "io/json_reader.h"
#include "io/output_file.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fibra {
namespace {

namespace fs = std::filesystem;

bool endsWithAny(const std::string& s, std::initializer_list<const char*> suffixes) {
  for (const char* suffix : suffixes)
    if (s.ends_with(suffix)) return true;
  return false;
}

std::string listOf(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The history file as gnuplot sees it from `pngDir`: relative when both are on one tree.
std::string relativeTo(const fs::path& file, const fs::path& pngDir) {
  const fs::path from = fs::weakly_canonical(fs::absolute(pngDir)),
                 to = fs::weakly_canonical(fs::absolute(file));
  const fs::path rel = to.lexically_relative(from);
  return rel.empty() ? to.string() : rel.string();
}

// argv[0] and the script for execv, as C strings built before fork (the child only calls
// async-signal-safe functions).
struct Child {
  std::string program, script, dir;
  int run(int errFd) const {
    const pid_t pid = fork();
    if (pid != 0) return pid;
    const int null = open("/dev/null", O_RDWR);
    if (null >= 0) {
      dup2(null, 0);
      dup2(null, 1);
    }
    dup2(errFd, 2);
    if (chdir(dir.c_str()) != 0) _exit(126);
    char* const argv[] = {const_cast<char*>(program.c_str()), const_cast<char*>(script.c_str()),
                          nullptr};
    execv(program.c_str(), argv);
    _exit(127);
  }
};

std::string readAll(int fd) {
  std::string out;
  char buffer[4096];
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    out.append(buffer, size_t(n));
  }
  return out;
}

std::string lastLines(std::string text, size_t maxChars) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (text.size() > maxChars) text = "..." + text.substr(text.size() - maxChars);
  return text;
}

}  // namespace

std::vector<std::string> readHistoryColumns(const std::string& path, bool needRows) {
  std::ifstream in(path);
  if (!in) {
    const bool running = fs::exists(path + ".part");
    throw PlotInputError(path + ": cannot read the history" +
                         (running ? std::string(" (the run is still going, or it was killed: ") +
                                        path + ".part; `fibra run --resume DIR` finishes a "
                                        "killed run)"
                                  : std::string(" (is it a fibra run's output directory?)")));
  }
  std::string header, row;
  if (!std::getline(in, header) || header.empty())
    throw PlotInputError(path + ": the history has no header line");
  if (needRows && !std::getline(in, row))
    throw PlotInputError(path + ": the history has no row (no converged increment)");
  std::vector<std::string> columns;
  std::istringstream names(header);
  for (std::string name; std::getline(names, name, ',');) columns.push_back(name);
  return columns;
}

std::string unknownColumn(const std::vector<std::string>& columns, const std::string& name) {
  const std::string close = json_reader::closestKey(name, columns);
  return "unknown column '" + name + "'" +
         (close.empty() ? "" : " (did you mean '" + close + "'?)") +
         "; the columns are: " + listOf(columns);
}

int findColumn(const std::vector<std::string>& columns, const std::string& name,
               const std::string& file, const std::string& what) {
  for (size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return int(i);
  throw PlotInputError(file + ": " + what + ": " + unknownColumn(columns, name));
}

std::vector<std::string> columnTerms(const std::string& entry) {
  std::vector<std::string> terms;
  std::istringstream in(entry);
  for (std::string term; std::getline(in, term, '+');) terms.push_back(term);
  if (entry.empty() || entry.back() == '+') terms.emplace_back();  // an empty last term
  return terms;
}

std::string columnUnit(const std::string& n) {
  if (n.find('+') != std::string::npos) {
    const std::vector<std::string> terms = columnTerms(n);
    const std::string unit = columnUnit(terms[0]);
    for (const std::string& t : terms)
      if (columnUnit(t) != unit) return "";
    return unit;
  }
  if (n == "wall_s") return "s";
  if (n.starts_with("energy.")) return "N mm";
  if (n == "contact.max_penetration" || n == "contact.max_overlap") return "mm";
  const bool forceOwner = n.starts_with("reaction.") || n.starts_with("tool.");
  if (forceOwner && endsWithAny(n, {".fx", ".fy", ".fz"})) return "N";
  if (n.starts_with("reaction.") && endsWithAny(n, {".mx", ".my", ".mz"})) return "N mm";
  if (n.starts_with("probe.") && endsWithAny(n, {".x", ".y", ".z"})) return "mm";
  if (n.starts_with("tool.") && endsWithAny(n, {".ux", ".uy", ".uz"})) return "mm";
  return "";  // counts, ratios, pseudo-time, and names not in the table
}

std::string axisLabel(const std::string& name) {
  const std::string unit = columnUnit(name);
  return unit.empty() ? name : name + " (" + unit + ")";
}

std::string axisLabel(const std::vector<std::string>& names) {
  bool shared = true;
  for (const std::string& n : names) shared = shared && columnUnit(n) == columnUnit(names[0]);
  if (!shared) {
    std::vector<std::string> labels;
    for (const std::string& n : names) labels.push_back(axisLabel(n));
    return listOf(labels);
  }
  const std::string unit = names.empty() ? "" : columnUnit(names[0]);
  return unit.empty() ? listOf(names) : listOf(names) + " (" + unit + ")";
}

std::string gnuplotString(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'')
      out += "''";
    else if (c == '\n' || c == '\r')
      out += ' ';
    else
      out += c;
  }
  return out + "'";
}

std::string pngTerminal(int width, int height) {
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  return "set encoding utf8\n"
         "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
         "  set terminal pngcairo size " + size + " noenhanced\n"
         "} else {\n"
         "  set terminal png size " + size + " noenhanced\n"
         "}\n";
}

std::string curveScript(const CurvePlot& plot, const std::vector<std::string>& columns,
                        const std::string& history, const std::string& png) {
  const int x = findColumn(columns, plot.x, history, "x") + 1;  // gnuplot counts from 1
  std::string s = "# fibra plot: " + listOf(plot.y) + " against " + plot.x + ", from " +
                  history + "\n# draw again, in this folder: gnuplot " +
                  fs::path(png).replace_extension(".gp").string() + "\n";
  s += pngTerminal(900, 600);
  s += "set output " + gnuplotString(png) + "\nset datafile separator ','\nset grid\n";
  if (!plot.title.empty()) s += "set title " + gnuplotString(plot.title) + "\n";
  s += "set xlabel " + gnuplotString(axisLabel(plot.x)) + "\n";
  s += "set ylabel " + gnuplotString(axisLabel(plot.y)) + "\nset key below noenhanced\n";
  for (size_t k = 0; k < plot.y.size(); ++k) {
    std::vector<std::string> terms;  // gnuplot's column numbers
    for (const std::string& term : columnTerms(plot.y[k]))
      terms.push_back(std::to_string(findColumn(columns, term, history, "y") + 1));
    std::string y = terms[0];  // "5", or "(column(5)+column(6))" for a sum
    if (terms.size() > 1) {
      y = "(";
      for (size_t t = 0; t < terms.size(); ++t)
        y += (t ? "+column(" : "column(") + terms[t] + ")";
      y += ")";
    }
    s += k == 0 ? "plot " + gnuplotString(history) : ", \\\n     ''";
    s += " skip 1 using " + std::to_string(x) + ":" + y +
         " with linespoints pt 7 ps 0.5 title " + gnuplotString(plot.y[k]);
  }
  return s + "\n";
}

std::string findGnuplot() {
  const char* chosen = std::getenv("FIBRA_GNUPLOT");
  const std::string name = chosen && *chosen ? chosen : "gnuplot";
  if (name.find('/') != std::string::npos)
    return access(name.c_str(), X_OK) == 0 ? name : "";
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    if (access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return candidate;
  }
  return "";
}

void runGnuplot(const std::string& script, const std::string& dir) {
  const std::string program = findGnuplot();
  const std::string where = (fs::path(dir) / script).lexically_normal().string();
  if (program.empty())
    throw PlotError("gnuplot not found (PATH, or FIBRA_GNUPLOT when set): install it (Debian: "
                    "apt-get install gnuplot-nox); the script " + where +
                    " draws the picture once it is there");
  int pipeFds[2];
  if (pipe2(pipeFds, O_CLOEXEC) != 0)  // close-on-exec: not inherited by other children
    throw PlotError("cannot start gnuplot: " + std::string(strerror(errno)));
  const Child child{program, script, dir.empty() ? "." : dir};
  const pid_t pid = child.run(pipeFds[1]);
  close(pipeFds[1]);
  if (pid < 0) {
    close(pipeFds[0]);
    throw PlotError("cannot start gnuplot: " + std::string(strerror(errno)));
  }
  const std::string messages = readAll(pipeFds[0]);
  close(pipeFds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  const std::string why = code == 126   ? "cannot enter the folder " + dir
                          : code == 127 ? "cannot execute " + program
                          : messages.empty() ? std::string("no message")
                                             : lastLines(messages, 600);
  throw PlotError(program + " failed on " + where + " (exit " +
                  std::to_string(code) + "): " + why);
}

std::string picturePath(const std::string& runDir, const std::string& file,
                        const std::string& fallback) {
  fs::path png = file.empty() ? fallback : file;
  if (png.is_relative()) png = fs::path(runDir) / png;
  if (png.extension() != ".png")
    throw PlotInputError(png.string() + ": the picture's name must end in .png");
  if (png.parent_path().empty()) png = fs::path(".") / png;
  std::error_code ec;
  fs::create_directories(png.parent_path(), ec);
  if (ec) throw PlotError("cannot create '" + png.parent_path().string() + "': " + ec.message());
  return png.string();
}

std::string drawCurves(const std::string& runDir, const CurvePlot& plot) {
  const fs::path history = fs::path(runDir) / "history.csv";
  const std::vector<std::string> columns = readHistoryColumns(history.string());
  if (plot.y.empty()) throw PlotInputError(history.string() + ": y: no column to draw");
  findColumn(columns, plot.x, history.string(), "x");
  for (const std::string& y : plot.y)
    for (const std::string& term : columnTerms(y)) findColumn(columns, term, history.string(), "y");
  const fs::path png = picturePath(runDir, plot.file);
  const fs::path dir = png.parent_path();
  return drawScript(png.string(),
                    curveScript(plot, columns, relativeTo(history, dir), png.filename().string()));
}

std::string drawScript(const std::string& pngPath, const std::string& text) {
  const fs::path png = pngPath;
  fs::path script = png;
  script.replace_extension(".gp");
  OutputFile file(script.string());
  file.stream() << text;
  file.commit();
  std::error_code ec;
  fs::remove(png, ec);  // so that a picture after the run is this run's
  // "./NAME": a name starting with '-' is not taken for an option
  runGnuplot("./" + script.filename().string(), png.parent_path().string());
  if (!fs::exists(png) || fs::file_size(png) == 0)
    throw PlotError(png.string() + ": gnuplot ran but wrote no picture");
  return script.string();
}

}  // namespace fibra
