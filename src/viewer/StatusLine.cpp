#include "viewer/StatusLine.h"

#include <cstdio>
#include <utility>

namespace penumbra::viewer {

void StatusLine::set(std::string message, bool isError) {
  text = std::move(message);
  error = isError;
  if (echo) std::fprintf(error ? stderr : stdout, "penumbra view: %s\n", text.c_str());
}

}  // namespace penumbra::viewer
