#include "srp/language/Tokenizer.h"

#include <cctype>

namespace srp::language {

std::string toLowerAscii(const std::string& s) {
  std::string out = s;
  for (auto& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

std::vector<std::string> toLowerAscii(const std::vector<std::string>& words) {
  std::vector<std::string> out;
  out.reserve(words.size());
  for (const auto& w : words) out.push_back(toLowerAscii(w));
  return out;
}

namespace {
bool isWordByte(unsigned char c) { return std::isalnum(c) || c == '-' || c == '\'' || c >= 0x80; }
bool isSpace(unsigned char c) { return std::isspace(c) != 0; }
}  // namespace

std::vector<std::vector<Token>> tokenizeSentences(const std::string& text) {
  std::vector<std::vector<Token>> sentences(1);
  const int n = static_cast<int>(text.size());
  auto closeSentence = [&]() {
    if (!sentences.back().empty()) sentences.emplace_back();
  };
  int i = 0;
  while (i < n) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (isSpace(c)) {
      // A blank line ends a sentence.
      if (c == '\n') {
        int k = i + 1;
        while (k < n && (text[k] == ' ' || text[k] == '\t' || text[k] == '\r')) ++k;
        if (k < n && text[k] == '\n') closeSentence();
      }
      ++i;
      continue;
    }
    if (isWordByte(c)) {
      int j = i;
      while (j < n) {
        const unsigned char d = static_cast<unsigned char>(text[j]);
        if (isWordByte(d)) {
          ++j;
        } else if (d == '.' && j + 1 < n && std::isdigit(static_cast<unsigned char>(text[j + 1])) && j > i &&
                   std::isdigit(static_cast<unsigned char>(text[j - 1]))) {
          ++j;  // decimal point
        } else {
          break;
        }
      }
      // Trailing '-' / '\'' are punctuation, not part of the word.
      while (j > i + 1 && (text[j - 1] == '-' || text[j - 1] == '\'')) --j;
      sentences.back().push_back({text.substr(i, j - i), i, j});
      i = j;
      continue;
    }
    sentences.back().push_back({std::string(1, static_cast<char>(c)), i, i + 1});
    const bool terminator = c == '.' || c == '!' || c == '?' || c == ';';
    ++i;
    if (terminator && (i >= n || isSpace(static_cast<unsigned char>(text[i])))) closeSentence();
  }
  if (sentences.back().empty()) sentences.pop_back();
  return sentences;
}

}  // namespace srp::language
