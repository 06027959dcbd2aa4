// The fuzz test's mutants and their verdicts (tests/test_scene_fuzz.cpp, docs/SCENE.md "Fuzz
// test"): which samples are mutated, how a mutant is made from a seed and its index, how it is
// run (tests/limited_child.h) and what it must end with.
#pragma once

#include "limited_child.h"
#include "scene_mutator.h"
#include "scene_test_util.h"

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

namespace fibra::test::fuzz {

// A sample as read, and its capped copy (one step, one increment, 1% of the first step's end
// time: a valid mutant of it solves in well under a second on the small samples).
struct Sample {
  std::string name, text, capped;
};

inline std::string cappedText(const std::string& text) {
  Json j = Json::parse(text, nullptr, true, true);
  Json& steps = j["steps"];
  steps.erase(steps.begin() + 1, steps.end());
  steps[0]["increments"] = 1;
  steps[0]["end_time"] = steps[0]["end_time"].get<double>() * 0.01;
  if (j.contains("output")) j["output"].erase("plots");  // no gnuplot per mutant
  return j.dump(2);
}

// samples/*.json, sorted by name.
inline std::vector<Sample> loadSamples() {
  std::vector<Sample> samples;
  for (const auto& e : fs::directory_iterator(sourcePath("samples")))
    if (e.path().extension() == ".json") {
      const std::string text = readFile(e.path().string());
      samples.push_back({e.path().stem().string(), text, cappedText(text)});
    }
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.name < b.name; });
  return samples;
}

struct Mutant {
  int index = 0;
  std::string sample, text, what;
  bool capped = false;  // made from the capped copy: a valid one may be run
};

// Mutant `index` of the seed, of sample index % samples. Of ten: five are one tree mutation of
// the capped copy, two are two, one is a tree and a text mutation of it, two a text mutation of
// the file as written (comments and all; never run, their steps are not capped).
inline Mutant makeMutant(const std::vector<Sample>& samples, std::uint64_t seed, int index) {
  SeededRandom rng(seed * 1000003 + std::uint64_t(index));
  const Sample& s = samples[size_t(index) % samples.size()];
  Mutant m{index, s.name, "", "", true};
  const int kind = rng.below(10);
  if (kind < 7 || kind == 9) {
    Json j = Json::parse(s.capped);
    for (int n = kind < 5 || kind == 9 ? 1 : 2; n > 0; --n) m.what += mutateTree(j, rng) + "; ";
    m.text = j.dump(2);
    if (kind < 7) return m;
  } else {
    m.text = s.text;
    m.capped = false;
  }
  m.what += mutateText(m.text, rng);
  return m;
}

inline std::uint64_t envNumber(const char* name, std::uint64_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtoull(v, nullptr, 10) : fallback;
}

// What a mutant's `fibra` ended with, and what is wrong with that ("" when nothing is).
struct Outcome {
  ChildResult result;
  std::string output;
};

inline bool mentionsCrash(const std::string& output) {
  for (const char* word : {"bad_alloc", "terminate called", "what()", "Assertion", "std::"})
    if (output.find(word) != std::string::npos) return true;
  return false;
}

// A refusal: "fibra: error: FILE: " then a field path or a line and column, then what is wrong.
inline bool namesFieldOrPlace(const std::string& output, const std::string& file) {
  const std::string prefix = "fibra: error: " + file + ": ";
  if (!output.starts_with(prefix)) return false;
  // A field path holds the keys as written, so any bytes ("tE,ables: unknown field").
  static const std::regex place(R"(^(line \d+, column \d+|[^\s:][^\n]*?): \S)");
  return std::regex_search(output.substr(prefix.size()), place);
}

inline std::string checkVerdict(const Outcome& o, const std::string& file) {
  if (o.result.terminated) return "check hung (wall-clock limit)";
  if (mentionsCrash(o.output)) return "check crashed or leaked an exception";
  if (o.result.status == 0)
    return o.output.ends_with("the scene is valid\n") ? "" : "check passed without saying so";
  if (o.result.status != 2) return "check ended with status " + std::to_string(o.result.status);
  return namesFieldOrPlace(o.output, file) ? "" : "refusal names no field nor line";
}

}  // namespace fibra::test::fuzz
