#include "srp/language/WordNetLexicon.h"

#include <wn.h>

#include <set>
#include <vector>

namespace srp::language {

namespace {
std::mutex& wordNetMutex() {
  static std::mutex m;
  return m;
}

bool initWordNet() {
  static const bool ok = [] { return wninit() == 0; }();
  return ok;
}

std::string baseForm(const std::string& word, int pos) {
  std::vector<char> buf(word.begin(), word.end());
  buf.push_back('\0');
  if (char* m = morphstr(buf.data(), pos)) return m;  // first base form
  std::vector<char> buf2(word.begin(), word.end());
  buf2.push_back('\0');
  IndexPtr idx = index_lookup(buf2.data(), pos);
  if (idx) {
    free_index(idx);
    return word;
  }
  return {};
}

// Marks classes found on the hypernym paths of the first senses of `lemma` (noun).
void classifyNoun(const std::string& lemma, WordInfo& info) {
  std::vector<char> buf(lemma.begin(), lemma.end());
  buf.push_back('\0');
  IndexPtr idx = index_lookup(buf.data(), NOUN);
  if (!idx) return;
  constexpr int kSenses = 4;    // later senses are rare readings
  constexpr int kMaxDepth = 18;  // WordNet noun trees are < 20 deep
  std::vector<std::pair<long, int>> stack;
  for (int s = 0; s < idx->off_cnt && s < kSenses; ++s) stack.push_back({static_cast<long>(idx->offset[s]), 0});
  free_index(idx);
  std::set<long> seen;
  static const std::set<std::string> kColour{"color", "colour", "chromatic_color", "achromatic_color"};
  static const std::set<std::string> kArtifact{"artifact", "artefact", "physical_object", "object", "whole"};
  static const std::set<std::string> kShape{"shape", "plane_figure", "solid", "polygon", "polyhedron"};
  static const std::set<std::string> kLocation{"location", "region", "surface", "side"};
  static const std::set<std::string> kRoom{"room", "building", "workplace", "place_of_business"};
  info.room |= kRoom.count(lemma) > 0;
  while (!stack.empty()) {
    const auto [offset, depth] = stack.back();
    stack.pop_back();
    if (!seen.insert(offset).second || depth > kMaxDepth) continue;
    static char empty[] = "";
    SynsetPtr ss = read_synset(NOUN, offset, empty);
    if (!ss) continue;
    for (int w = 0; w < ss->wcount; ++w) {
      const std::string word = ss->words[w];
      if (depth > 0 || word != lemma) {
        info.colour |= kColour.count(word) > 0;
        info.artifact |= kArtifact.count(word) > 0;
        info.shape |= kShape.count(word) > 0;
        info.location |= kLocation.count(word) > 0;
        info.room |= kRoom.count(word) > 0;
      }
    }
    for (int p = 0; p < ss->ptrcount; ++p)
      if (ss->ptrtyp[p] == HYPERPTR || ss->ptrtyp[p] == INSTANCE) stack.push_back({ss->ptroff[p], depth + 1});
    free_synset(ss);
  }
}
}  // namespace

WordNetLexicon::WordNetLexicon() {
  std::lock_guard<std::mutex> lock(wordNetMutex());
  available_ = initWordNet();
}

WordInfo WordNetLexicon::lookup(const std::string& lowerWord) const {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = cache_.find(lowerWord);
    if (it != cache_.end()) return it->second;
  }
  WordInfo info;
  const bool plausible = !lowerWord.empty() && lowerWord.size() < 64 &&
                         lowerWord.find_first_not_of("abcdefghijklmnopqrstuvwxyz-'") == std::string::npos;
  if (available_ && plausible) {
    std::lock_guard<std::mutex> lock(wordNetMutex());
    info.nounLemma = baseForm(lowerWord, NOUN);
    info.verbLemma = baseForm(lowerWord, VERB);
    info.noun = !info.nounLemma.empty();
    info.verb = !info.verbLemma.empty();
    info.adjective = !baseForm(lowerWord, ADJ).empty();
    info.adverb = !baseForm(lowerWord, ADV).empty();
    if (info.noun) classifyNoun(info.nounLemma, info);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  cache_.emplace(lowerWord, info);
  return info;
}

}  // namespace srp::language
