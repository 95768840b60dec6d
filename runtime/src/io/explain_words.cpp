#include "io/explain_words.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace lrigid {

namespace {

bool has(const nlohmann::json& names, const char* effect) {
  return std::find(names.begin(), names.end(), effect) != names.end();
}

std::string speed(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2g m/s", v);
  return b;
}

// x to two significant digits, without an exponent (150, 2.1, 0.35)
std::string two_digits(double x) {
  char b[32];
  std::snprintf(b, sizeof b, x >= 10 ? "%.0f" : "%.2g", x);
  return b;
}

}  // namespace

std::string plain_words(const nlohmann::json& t, const nlohmann::json& j) {
  const bool water = j["fluid"]["density"].get<double>() >= 100;
  const char* fluid = water ? "water" : "air";
  const nlohmann::json& sim = t["simulated"];
  std::vector<std::string> parts;

  // turbulence: the Stokes number on the energetic eddies' time k/eps
  const double k = j["flow"]["k"].get<double>(), st = t["stokes_k_eps"].get<double>();
  if (!(k > 0))
    parts.push_back("no turbulence moves it (the flow has none)");
  else if (!has(sim, "turbulence"))
    parts.push_back(t["scene_lists"].is_null()
                        ? "turbulence barely moves it, so it is not simulated"
                        : "the scene leaves turbulence out for it");
  else if (st < 0.1 && t["stokes_kolmogorov"].get<double>() > 1)
    parts.push_back(std::string("light enough to follow the large, slow eddies of the ") + fluid +
                    ", but not its smallest, quickest ones");
  else if (st < 0.1)
    parts.push_back(std::string("light enough to follow the gusts and eddies of the ") + fluid +
                    " closely, even the smallest");
  else if (st < 3)
    parts.push_back("turbulence shakes it noticeably, but it lags behind the quicker eddies");
  else
    parts.push_back("heavy enough that turbulence barely moves it");

  // crossing trajectories: a drift through the eddies shortens what it sees of them
  const nlohmann::json& ct = t["crossing_trajectories"];
  if (ct["on"].get<bool>() && ct["factor_across"].get<double>() >= 1.2)
    parts.push_back("it drifts through the eddies at " +
                    two_digits(ct["drift_over_u_turb"].get<double>()) +
                    " times their speed, so they spread it sideways about " +
                    two_digits(ct["factor_across"].get<double>()) + " times less than the " +
                    fluid + " itself");

  // settling: falls, rises, or floats
  const double ratio = t["density_ratio"].get<double>(), vt = t["terminal_speed"].get<double>();
  if (ratio > 1.02)
    parts.push_back("rises at about " + speed(vt) + " (lighter than the " + fluid + ")");
  else if (ratio >= 0.98)
    parts.push_back(std::string("about as dense as the ") + fluid + ", so it hardly falls or rises");
  else
    parts.push_back("falls at about " + speed(vt));

  // shape
  if (t["flat"].get<bool>())
    parts.push_back(has(sim, "lift") ? "its flat shape makes it flutter and tumble"
                                     : "it is flat, but lift is off, so it does not flutter");
  else if (t["aspect_ratio"].get<double>() < 0.5)
    parts.push_back("its elongated shape makes it turn as it moves");
  else if (t["shape"] == "sphere")
    parts.push_back("round, so it does not flutter");
  if (has(sim, "magnus")) parts.push_back("its spin curves its path");

  // the mean flow against the settling speed
  const double U = j["flow"]["U"].get<double>();
  if (has(sim, "mean_flow") && U > 0)
    parts.push_back(U > vt ? "the " + std::string(fluid) + " (" + speed(U) +
                                 ") carries it sideways faster than it " +
                                 (ratio > 1.02 ? "rises" : "falls")
                           : "it " + std::string(ratio > 1.02 ? "rises" : "falls") +
                                 " faster than the " + fluid + " (" + speed(U) + ") carries it");

  std::string s;
  for (size_t i = 0; i < parts.size(); ++i) s += (i ? "; " : "") + parts[i];
  if (!s.empty()) s[0] = char(std::toupper(static_cast<unsigned char>(s[0])));
  return s + ".";
}

}  // namespace lrigid
