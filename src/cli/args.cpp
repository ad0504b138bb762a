#include "cli/args.h"

#include <cmath>

#include <cstdlib>

#include "tsp/core/error.h"

namespace tspcli {

long long parse_integer(const std::string& text, const std::string& option, long long lo,
                        long long hi, const std::string& expected) {
  std::size_t used = 0;
  long long v = 0;
  bool ok = !text.empty() && text[0] != '+' && text[0] != ' ';
  if (ok) {
    try {
      v = std::stoll(text, &used);
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok || used != text.size() || v < lo || v > hi)
    throw tsp::UsageError(option + " '" + text + "': expected " + expected);
  return v;
}

double parse_number(const std::string& text, const std::string& option) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    throw tsp::UsageError(option + " '" + text + "': not a number");
  return v;
}

std::array<double, 3> parse_triple(const std::string& text, const std::string& option,
                                   const std::string& expected) {
  std::array<double, 3> v{};
  std::size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t comma = text.find(',', start);
    if ((k < 2) != (comma != std::string::npos))
      throw tsp::UsageError(option + " '" + text + "': expected " + expected);
    try {
      v[std::size_t(k)] = parse_number(text.substr(start, comma - start), option);
    } catch (const tsp::UsageError&) {
      throw tsp::UsageError(option + " '" + text + "': expected " + expected);
    }
    if (!std::isfinite(v[std::size_t(k)]))  // nan, inf: no triple of ours means them
      throw tsp::UsageError(option + " '" + text + "': expected " + expected +
                            ", three finite numbers");
    start = comma + 1;
  }
  return v;
}

tsp::Dims parse_dims(const std::string& text, const std::string& option, int max_edge,
                     bool allow_cube) {
  const std::string expected = std::string(allow_cube ? "X,Y,Z or N" : "X,Y,Z") +
                               " with every edge in [1, " + std::to_string(max_edge) + "]";
  int v[3];
  std::size_t pos = 0;
  int n = 0;
  for (; n < 3; ++n) {
    std::size_t comma = text.find(',', pos);
    std::string part = text.substr(pos, comma == std::string::npos ? comma : comma - pos);
    v[n] = int(parse_integer(part, option, 1, max_edge, expected));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  if (n == 0 && allow_cube) return {v[0], v[0], v[0]};
  if (n != 2 || text.find(',', pos) != std::string::npos)
    throw tsp::UsageError(option + " '" + text + "': expected " + expected);
  return {v[0], v[1], v[2]};
}

tsp::ValueRange parse_range(const std::string& text, const std::string& option) {
  auto colon = text.find(':', 1);  // a leading '-' is a sign, never the separator
  if (colon == std::string::npos)
    throw tsp::UsageError(option + " '" + text + "': expected LO:HI, e.g. " + option + "=-5:40");
  return {parse_number(text.substr(0, colon), option),
          parse_number(text.substr(colon + 1), option)};
}

StepRange parse_steps(const std::string& text) {
  if (text.empty()) return {};
  const std::string expected = "A:B, A:, A or A:B:S with step numbers from 0 and a stride S >= 1";
  auto part = [&](const std::string& s, long long lo) {
    try {
      return int(parse_integer(s, "--steps", lo, 1 << 30, expected));
    } catch (const tsp::UsageError&) {
      throw tsp::UsageError("--steps '" + text + "': expected " + expected);
    }
  };
  const auto c1 = text.find(':');
  StepRange r;
  r.first = part(text.substr(0, c1), 0);
  if (c1 == std::string::npos) {
    r.last = r.first;
    return r;
  }
  const auto c2 = text.find(':', c1 + 1);
  const std::string b = text.substr(c1 + 1, c2 == std::string::npos ? std::string::npos : c2 - c1 - 1);
  r.last = b.empty() ? -1 : part(b, 0);
  if (c2 != std::string::npos) r.stride = part(text.substr(c2 + 1), 1);
  return r;
}

std::pair<int, int> parse_size(const std::string& text) {
  auto x = text.find('x');
  if (x == std::string::npos) throw tsp::UsageError("--size '" + text + "': expected WxH");
  return {int(parse_integer(text.substr(0, x), "--size", 1, 8192, "WxH, 1..8192")),
          int(parse_integer(text.substr(x + 1), "--size", 1, 8192, "WxH, 1..8192"))};
}

}  // namespace tspcli
