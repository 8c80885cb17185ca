#pragma once
// The viewer's status line: the latest action or problem, shown at the top of the panels. Every
// part of the viewer reports to it; a scripted or verbose run also writes it out (errors on
// stderr), so a script's log says what a user would have read.
#include <string>

namespace penumbra::viewer {

struct StatusLine {
  std::string text;
  bool error = false;
  bool echo = false;  ///< also print each message ("penumbra view: …")

  void set(std::string message, bool isError);
};

}  // namespace penumbra::viewer
