// Output files that are never half-written, and the number format every writer uses.
//
// An OutputFile collects its text in PATH.part and renames it to PATH on commit(): a reader
// (ParaView, a plotting script) sees either the previous complete file or the new complete one,
// never a truncated one, even when the program is interrupted. Not thread-safe; one writer per
// file.
#pragma once

#include <fstream>
#include <string>

namespace fibra {

class OutputFile {
 public:
  explicit OutputFile(std::string path);  // opens PATH.part; throws std::runtime_error
  ~OutputFile();                          // not committed: removes PATH.part
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return out_; }
  void flush();   // throws std::runtime_error when the data could not be written
  void commit();  // flush, close, rename PATH.part -> PATH; throws std::runtime_error
  bool committed() const { return committed_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_, partPath_;
  std::ofstream out_;
  bool committed_ = false;
};

// The whole content of a file; std::runtime_error "cannot read PATH" when it cannot be read.
std::string readWholeFile(const std::string& path);

// Shortest decimal that reads back as exactly v ("0.1", "3", "-2.5e-07", "nan", "inf").
void appendNumber(std::string& out, double v);

}  // namespace fibra
