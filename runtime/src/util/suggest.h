// "Did you mean ...?": the nearest valid name to a mistyped one (scene keys, command-line
// flags of lrigid and foam2grid). Header-only so that the converter can use it too.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

namespace lrigid {

// Edits (insert, delete, substitute, swap two neighbours) turning a into b.
inline size_t edit_distance(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 1; j <= m; ++j) {
      const size_t sub = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + sub});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

// The candidate closest to `word`, or "" when none is close: at most 2 edits, or a third of
// the word's length for long words, and never all of it.
inline std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : names) {
    const size_t d = edit_distance(word, c);
    if (d < best_d && d < std::max(word.size(), c.size())) best = c, best_d = d;
  }
  return best;
}

// " (did you mean "x"?)" or ""
inline std::string did_you_mean(const std::string& word, const std::vector<std::string>& names) {
  const std::string n = nearest_name(word, names);
  return n.empty() ? "" : " (did you mean \"" + n + "\"?)";
}

}  // namespace lrigid
