#include "io/output_file.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace fibra {

std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (!(in && text << in.rdbuf()) || std::filesystem::is_directory(path))
    throw std::runtime_error("cannot read " + path);
  return text.str();
}

OutputFile::OutputFile(std::string path)
    : path_(std::move(path)), partPath_(path_ + ".part"), out_(partPath_, std::ios::binary) {
  if (!out_) throw std::runtime_error("cannot write " + partPath_);
}

OutputFile::~OutputFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(partPath_, ignored);
}

void OutputFile::flush() {
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write " + partPath_ + " (disk full?)");
}

void OutputFile::commit() {
  flush();
  out_.close();
  if (!out_) throw std::runtime_error("cannot write " + partPath_);
  std::error_code ec;
  std::filesystem::rename(partPath_, path_, ec);
  if (ec)
    throw std::runtime_error("cannot rename " + partPath_ + " to " + path_ + ": " + ec.message());
  committed_ = true;
}

void appendNumber(std::string& out, double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, r.ptr);
}

}  // namespace fibra
