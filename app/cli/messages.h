// How a command prints a refusal: one line, whatever the message holds (a file name or an argument
// with a newline in it, a library's two-line text). main.cpp, the commands and the fuzz entries share it.
#pragma once
#include <string>

namespace gb {

// `message` with each newline as "; " (a trailing one dropped).
inline std::string oneLine(std::string message) {
  while (!message.empty() && message.back() == '\n') message.pop_back();
  for (size_t at; (at = message.find('\n')) != std::string::npos;) message.replace(at, 1, "; ");
  return message;
}

}  // namespace gb
