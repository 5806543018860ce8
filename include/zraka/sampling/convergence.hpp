#pragma once
// The "error against run time" record every Monte Carlo chapter keeps (book 1.6): one row per
// run with N = 2^k samples, its wall-clock seconds, and named value columns; a least-squares fit
// of log(error) against log(N), whose slope is -1/2 for an unbiased Monte Carlo estimator; an
// aligned table for the terminal; and a CSV file (written atomically) for
// tools/plot_convergence.py.
//
// The columns after n and seconds are named by the caller:
//  - an integral with a known value:  n, seconds, estimate, abs_error, std_error
//    (convergence_log::add(n, seconds, estimator, reference) fills them);
//  - a renderer against a reference image: name the first column "spp" and the rest
//    {"rmse", "relmse"}, fit column "rmse", and add(spp, seconds, {rmse, relmse}).
//    (relMSE falls as 1/N, so its own slope is -1.)
#include <zraka/core/atomic_file.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/sampling/estimator.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace zraka {

struct convergence_row {
  std::uint64_t n = 0;          // samples (per pixel, for a renderer)
  double seconds = 0;           // wall-clock time this row's estimate took
  std::vector<double> values;   // one per named column
};

// Least-squares line y = intercept + slope * x through points (ln n, ln value).
struct loglog_fit {
  double slope = std::numeric_limits<double>::quiet_NaN();
  double intercept = std::numeric_limits<double>::quiet_NaN();
  double slope_stderr = std::numeric_limits<double>::quiet_NaN();  // from the residuals
  std::size_t points = 0;
};

// Fits ln y = a + b ln x, skipping points that have no logarithm (below).
ZRAKA_COMPILED_FN loglog_fit fit_loglog(const std::vector<double>& x, const std::vector<double>& y);

class convergence_log {
 public:
  // The columns of an integral with a known value.
  static std::vector<std::string> integral_columns() {
    return {"estimate", "abs_error", "std_error"};
  }

  // `columns` name the values of each row; `fit_column` is the error the slope is fitted to.
  ZRAKA_COMPILED_FN explicit convergence_log(std::string title, std::vector<std::string> columns = integral_columns(),
                                             std::string fit_column = "abs_error", std::string n_name = "n");

  ZRAKA_COMPILED_FN void add(std::uint64_t n, double seconds, std::vector<double> values);

  // A Monte Carlo integral against its known value (the integral_columns() layout).
  void add(double seconds, const estimator& e, double reference) {
    add(e.count(), seconds, {e.mean(), std::abs(e.mean() - reference), e.standard_error()});
  }

  const std::string& title() const { return title_; }
  const std::string& n_name() const { return n_name_; }
  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<convergence_row>& rows() const { return rows_; }

  std::size_t column_index(std::string_view name) const {
    const auto it = std::find(columns_.begin(), columns_.end(), name);
    if (it == columns_.end())
      throw error("convergence_log '" + title_ + "' has no column '" + std::string(name) + "'");
    return std::size_t(it - columns_.begin());
  }

  // Slope of ln(column) against ln(n); the fit column unless another is named.
  ZRAKA_COMPILED_FN loglog_fit fit(std::string_view column = {}) const;

  // The aligned table: a title line, a header and one line per row. NaN prints as n/a.
  ZRAKA_COMPILED_FN std::string table() const;

  // One line: the fitted slope of the fit column, with its standard error.
  ZRAKA_COMPILED_FN std::string slope_line(std::string_view column = {}) const;

  // CSV: a header line (n, seconds, columns...) and full-precision rows ("nan" for NaN).
  ZRAKA_COMPILED_FN std::string csv() const;

  void write_csv(const std::filesystem::path& path) const { write_file_atomically(path, csv()); }

  // Reads what csv() wrote; the title becomes the file name. The fit column is "abs_error" if
  // there is one, else the first value column (rmse for a renderer), unless `fit_column` says.
  static convergence_log read_csv(const std::filesystem::path& path, std::string fit_column = {}) {
    std::ifstream in(path);
    if (!in) throw error("cannot read " + path.string());
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_csv(ss.str(), path.filename().string(), std::move(fit_column));
  }

  static convergence_log parse_csv(const std::string& text, std::string title,
                                   std::string fit_column = {}) {
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line)) throw error(title + ": empty CSV");
    const auto head = split(line);
    if (head.size() < 3 || head[1] != "seconds")
      throw error(title + ": CSV header must be <n>,seconds,<columns...>, got '" + line + "'");
    std::vector<std::string> cols(head.begin() + 2, head.end());
    if (fit_column.empty())
      fit_column = std::find(cols.begin(), cols.end(), "abs_error") != cols.end() ? "abs_error"
                                                                                : cols.front();
    convergence_log log(std::move(title), cols, fit_column, head[0]);
    for (int lineno = 2; std::getline(in, line); ++lineno) {
      if (line.empty()) continue;
      const auto f = split(line);
      if (f.size() != head.size())
        throw error(log.title_ + ":" + std::to_string(lineno) + ": expected " +
                    std::to_string(head.size()) + " fields, got " + std::to_string(f.size()));
      std::vector<double> v;
      for (std::size_t i = 2; i < f.size(); ++i) v.push_back(number(f[i], log.title_, lineno));
      log.add(std::uint64_t(number(f[0], log.title_, lineno)), number(f[1], log.title_, lineno),
              std::move(v));
    }
    return log;
  }

 private:
  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ',')) out.push_back(field);
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
  }
  static double number(const std::string& s, const std::string& title, int lineno) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0')
      throw error(title + ":" + std::to_string(lineno) + ": '" + s + "' is not a number");
    return v;
  }

  std::string title_, n_name_;
  std::vector<std::string> columns_;
  std::string fit_column_;
  std::vector<convergence_row> rows_;
};

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
ZRAKA_COMPILED_FN convergence_log::convergence_log(std::string title, std::vector<std::string> columns,
                                                  std::string fit_column, std::string n_name)
    : title_(std::move(title)), n_name_(std::move(n_name)), columns_(std::move(columns)),
      fit_column_(std::move(fit_column)) {
  column_index(fit_column_);  // throws if the fit column is not one of the columns
}

// [listing loglog-fit]
// Fits ln y = a + b ln x. Points with x or y not positive and finite are skipped (an exact
// zero error has no logarithm), so the fit needs at least two usable points.
ZRAKA_COMPILED_FN loglog_fit fit_loglog(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<std::pair<double, double>> p;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (x[i] > 0 && y[i] > 0 && std::isfinite(x[i]) && std::isfinite(y[i]))
      p.emplace_back(std::log(x[i]), std::log(y[i]));
  loglog_fit f;
  f.points = p.size();
  if (p.size() < 2) return f;
  double mx = 0, my = 0;  // centre first: sums of centred products do not cancel
  for (auto [u, v] : p) mx += u, my += v;
  mx /= double(p.size()), my /= double(p.size());
  double sxx = 0, sxy = 0;
  for (auto [u, v] : p) sxx += (u - mx) * (u - mx), sxy += (u - mx) * (v - my);
  if (!(sxx > 0)) return f;  // all n equal: no slope
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  if (p.size() > 2) {
    double rss = 0;
    for (auto [u, v] : p) rss += std::pow(v - f.intercept - f.slope * u, 2);
    f.slope_stderr = std::sqrt(rss / double(p.size() - 2) / sxx);
  }
  return f;
}
// [end]

ZRAKA_COMPILED_FN void convergence_log::add(std::uint64_t n, double seconds, std::vector<double> values) {
  if (values.size() != columns_.size())
    throw error("convergence_log '" + title_ + "': a row needs " + std::to_string(columns_.size()) +
                " values, got " + std::to_string(values.size()));
  rows_.push_back({n, seconds, std::move(values)});
}

ZRAKA_COMPILED_FN loglog_fit convergence_log::fit(std::string_view column) const {
  const std::size_t c = column_index(column.empty() ? std::string_view(fit_column_) : column);
  std::vector<double> x, y;
  for (const auto& r : rows_) x.push_back(double(r.n)), y.push_back(r.values[c]);
  return fit_loglog(x, y);
}

ZRAKA_COMPILED_FN std::string convergence_log::table() const {
  std::string s = title_ + "\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%12s %11s", n_name_.c_str(), "seconds");
  s += buf;
  for (const auto& c : columns_) std::snprintf(buf, sizeof buf, " %14s", c.c_str()), s += buf;
  s += "\n";
  for (const auto& r : rows_) {
    std::snprintf(buf, sizeof buf, "%12llu %11.3e", static_cast<unsigned long long>(r.n),
                  r.seconds);
    s += buf;
    for (double v : r.values) {
      if (std::isnan(v))
        std::snprintf(buf, sizeof buf, " %14s", "n/a");
      else
        std::snprintf(buf, sizeof buf, " %14.7g", v);
      s += buf;
    }
    s += "\n";
  }
  return s;
}

ZRAKA_COMPILED_FN std::string convergence_log::slope_line(std::string_view column) const {
  const std::string name(column.empty() ? std::string_view(fit_column_) : column);
  const loglog_fit f = fit(name);
  char buf[160];
  if (std::isnan(f.slope))
    std::snprintf(buf, sizeof buf, "slope of log(%s) vs log(%s): n/a (%zu usable rows)",
                  name.c_str(), n_name_.c_str(), f.points);
  else
    std::snprintf(buf, sizeof buf, "slope of log(%s) vs log(%s): %+.3f +- %.3f (%zu rows)",
                  name.c_str(), n_name_.c_str(), f.slope, f.slope_stderr, f.points);
  return buf;
}

ZRAKA_COMPILED_FN std::string convergence_log::csv() const {
  std::string s = n_name_ + ",seconds";
  for (const auto& c : columns_) s += "," + c;
  s += "\n";
  char buf[40];
  for (const auto& r : rows_) {
    s += std::to_string(r.n);
    std::snprintf(buf, sizeof buf, ",%.17g", r.seconds), s += buf;
    for (double v : r.values) std::snprintf(buf, sizeof buf, ",%.17g", v), s += buf;
    s += "\n";
  }
  return s;
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka
