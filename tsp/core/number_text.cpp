#include "tsp/core/number_text.h"

#include <cstdio>

namespace tsp {

std::string number_text(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace tsp
