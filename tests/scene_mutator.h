// Seeded mutants of a scene for the fuzz test (tests/test_scene_fuzz.cpp). A mutant is made from
// one sample by a SeededRandom (io/seeded_random.h) alone, so the same seed gives the same mutant
// on every machine. Mutations of the JSON tree: a field or array item deleted, a value of the
// wrong type (string, array, object, null, boolean), an extreme number (0, -1, +-1e308, 1e-308,
// huge integers), a huge count (elements, increments, fibres, rings, sectors, ...), an empty
// array or object. Mutations of the text: truncated at a random point, random bytes inserted,
// a key repeated in its object.
#pragma once

#include "io/seeded_random.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace fibra::test::fuzz {

using Json = nlohmann::json;
using Pointer = Json::json_pointer;

// Keys whose value sizes memory or time: the huge-count mutation aims at these.
inline const std::vector<std::string>& countKeys() {
  static const std::vector<std::string> keys{
      "elements", "increments", "fibres", "rings", "sectors", "order", "yarns",
      "fibres_per_yarn", "modes", "max_iterations", "max_cutbacks", "output_every", "node",
      "seed", "axial", "section", "levels"};
  return keys;
}

template <class T>
const T& pick(SeededRandom& rng, const std::vector<T>& v) {
  return v[size_t(rng.below(int(v.size())))];
}

// Every value below the root, as pointers (depth first).
inline void collectPointers(const Json& j, const Pointer& at, std::vector<Pointer>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      out.push_back(at / key);
      collectPointers(value, at / key, out);
    }
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) {
      out.push_back(at / i);
      collectPointers(j[i], at / i, out);
    }
  }
}

inline std::vector<Pointer> pointersOf(const Json& j) {
  std::vector<Pointer> out;
  collectPointers(j, Pointer(), out);
  return out;
}

inline Json wrongType(SeededRandom& rng) {
  const Json choices[] = {"x", "1e3", "", Json::array(), Json::array({1, 2}), Json::object(),
                          Json{{"a", 1}}, nullptr, true, false};
  return choices[rng.below(int(std::size(choices)))];
}

inline Json extremeNumber(SeededRandom& rng) {
  const Json choices[] = {0, -1, 1e308, -1e308, 1e-308, -1e-308, 0.5, 2147483647,
                          std::uint64_t(2147483648), -2147483648LL, std::uint64_t(1) << 62,
                          std::uint64_t(18446744073709551615ULL), 1e20, 3.5e9};
  return choices[rng.below(int(std::size(choices)))];
}

inline Json hugeCount(SeededRandom& rng) {
  const Json choices[] = {0, -1, 1000000, 10000000, 100000000, 2147483647,
                          std::uint64_t(2147483648), std::uint64_t(1) << 40, 1e300, 2.5};
  return choices[rng.below(int(std::size(choices)))];
}

inline void erase(Json& root, const Pointer& p) {
  Json& parent = root[p.parent_pointer()];
  if (parent.is_object())
    parent.erase(p.back());
  else
    parent.erase(size_t(std::stoul(p.back())));
}

// Pointers whose last key is a count key.
inline std::vector<Pointer> countPointers(const std::vector<Pointer>& all) {
  std::vector<Pointer> out;
  for (const Pointer& p : all)
    for (const std::string& k : countKeys())
      if (p.back() == k) out.push_back(p);
  return out;
}

// Pointers to numbers.
inline std::vector<Pointer> numberPointers(const Json& root, const std::vector<Pointer>& all) {
  std::vector<Pointer> out;
  for (const Pointer& p : all)
    if (root[p].is_number()) out.push_back(p);
  return out;
}

// One mutation of the tree; returns what it did (for the report of a failing mutant).
inline std::string mutateTree(Json& root, SeededRandom& rng) {
  const std::vector<Pointer> all = pointersOf(root);
  if (all.empty()) return "nothing to mutate";
  const Pointer p = pick(rng, all);
  switch (rng.below(5)) {
    case 0:
      erase(root, p);
      return "deleted " + p.to_string();
    case 1:
      root[p] = wrongType(rng);
      return "wrong type at " + p.to_string() + ": " + root[p].dump();
    case 2: {
      const std::vector<Pointer> numbers = numberPointers(root, all);
      const Pointer n = numbers.empty() ? p : pick(rng, numbers);
      root[n] = extremeNumber(rng);
      return "extreme number at " + n.to_string() + ": " + root[n].dump();
    }
    case 3: {
      const std::vector<Pointer> counts = countPointers(all);
      const Pointer c = counts.empty() ? p : pick(rng, counts);
      root[c] = hugeCount(rng);
      return "huge count at " + c.to_string() + ": " + root[c].dump();
    }
    default:
      root[p] = rng.below(2) ? Json::array() : Json::object();
      return "emptied " + p.to_string() + ": " + root[p].dump();
  }
}

// Offsets of the keys ("name" followed by ':') in JSON text.
inline std::vector<size_t> keyOffsets(const std::string& text) {
  std::vector<size_t> out;
  for (size_t q = text.find('"'); q != std::string::npos;) {
    const size_t end = text.find('"', q + 1);
    if (end == std::string::npos) break;
    size_t after = end + 1;
    while (after < text.size() && (text[after] == ' ' || text[after] == '\n')) ++after;
    if (after < text.size() && text[after] == ':') out.push_back(q);
    q = text.find('"', after);
  }
  return out;
}

// One mutation of the text; returns what it did.
inline std::string mutateText(std::string& text, SeededRandom& rng) {
  const size_t at = size_t(rng.below(int(text.size()) + 1));
  switch (rng.below(3)) {
    case 0:
      text.resize(at);
      return "truncated at byte " + std::to_string(at);
    case 1: {
      std::string bytes(size_t(1 + rng.below(8)), ' ');
      for (char& c : bytes) c = char(rng.below(256));
      text.insert(at, bytes);
      return "inserted " + std::to_string(bytes.size()) + " random bytes at byte " +
             std::to_string(at);
    }
    default: {
      const std::vector<size_t> keys = keyOffsets(text);
      if (keys.empty()) return "no key to repeat";
      const size_t k = pick(rng, keys);
      const std::string key = text.substr(k, text.find('"', k + 1) - k + 1);
      text.insert(k, key + ": 1, ");
      return "repeated key " + key + " at byte " + std::to_string(k);
    }
  }
}

}  // namespace fibra::test::fuzz
