#pragma once
/// \file Tokenizer.h
/// \brief Sentence splitting and word tokenisation of an instruction, keeping
/// each token's byte offsets in the input text.

#include <string>
#include <vector>

namespace srp::language {

/// One word or punctuation mark: the text as written and its byte range
/// [charBegin, charEnd) in the input.
struct Token {
  std::string text;
  int charBegin = 0, charEnd = 0;
};

/// Splits `text` into sentences (at '.', '!', '?', ';' followed by white space or
/// the end, and at blank lines) and each sentence into tokens: runs of letters,
/// digits, '-' and '\'' form words; other visible characters are one token each.
/// A '.' between digits ("2.5") stays in the number. Never throws.
std::vector<std::vector<Token>> tokenizeSentences(const std::string& text);

/// Lower-cases ASCII letters (the corpus is English; other bytes are kept).
std::string toLowerAscii(const std::string& s);
/// Every word of `words` lower-cased (toLowerAscii).
std::vector<std::string> toLowerAscii(const std::vector<std::string>& words);

}  // namespace srp::language
