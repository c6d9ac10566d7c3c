// SPDX-License-Identifier: BSD-3-Clause
#include "scene/BrdfTable.h"

#include "math/Constants.h"

#include "scene/InputError.h"
#include "scene/InputFile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <sstream>

namespace sphcover
{
namespace
{
const char* const Header = "theta_in,theta_out,delta_phi,r,g,b";

std::string Trim(const std::string& text)
{
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos)
  {
    return std::string();
  }
  const auto end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

std::vector<std::string> SplitFields(const std::string& line)
{
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ','))
  {
    fields.push_back(Trim(field));
  }
  if (!line.empty() && line.back() == ',')
  {
    fields.emplace_back();
  }
  return fields;
}

/// The position of `value` in the ascending `grid` as a cell index and a fraction, clamped.
void Locate(const std::vector<double>& grid, double value, std::size_t& cell, double& t)
{
  if (grid.size() == 1 || value <= grid.front())
  {
    cell = 0;
    t = 0.0;
    return;
  }
  if (value >= grid.back())
  {
    cell = grid.size() - 2;
    t = 1.0;
    return;
  }
  cell =
    static_cast<std::size_t>(std::upper_bound(grid.begin(), grid.end(), value) - grid.begin()) - 1;
  t = (value - grid[cell]) / (grid[cell + 1] - grid[cell]);
}

/// One data row of the CSV: theta_in, theta_out, delta_phi (degrees), r, g, b, and its line.
struct CsvRow
{
  double Values[6];
  int Line;
};

/// A row's point in the grid of the distinct angles, and the row's index.
struct GridEntry
{
  std::array<std::size_t, 3> Cell;
  std::size_t Row;
};

/// Throws InputError(name, "line L" (none for line 0), problem).
[[noreturn]] void Fail(const std::string& name, int line, const std::string& problem)
{
  throw InputError(name, line > 0 ? "line " + std::to_string(line) : "", problem);
}

/// The data line `trimmed` (line `line`) as a row: 6 finite numbers, the angles in range, the
/// BRDF values >= 0.
CsvRow ParseRow(const std::string& trimmed, int line, const std::string& name)
{
  const std::vector<std::string> fields = SplitFields(trimmed);
  if (fields.size() != 6)
  {
    Fail(name, line, "expected 6 comma-separated numbers, got " + std::to_string(fields.size()));
  }
  CsvRow row{};
  row.Line = line;
  for (int k = 0; k < 6; ++k)
  {
    const std::string& field = fields[static_cast<std::size_t>(k)];
    char* end = nullptr;
    const double value = field.empty() ? 0.0 : std::strtod(field.c_str(), &end);
    if (field.empty() || end != field.c_str() + field.size())
    {
      Fail(name, line, "expected a number in column " + std::to_string(k + 1));
    }
    // strtod's ERANGE also flags underflow (1e-310 is subnormal, 1e-400 rounds to 0): such
    // values are harmless and read as rounded; only overflow and nan/inf are errors.
    if (!std::isfinite(value))
    {
      Fail(name, line, "not a finite number in column " + std::to_string(k + 1));
    }
    row.Values[k] = value;
  }
  if (row.Values[0] < 0.0 || row.Values[0] > 90.0 || row.Values[1] < 0.0 || row.Values[1] > 90.0)
  {
    Fail(name, line, "theta_in and theta_out must be in [0, 90] degrees");
  }
  if (row.Values[2] < 0.0 || row.Values[2] > 180.0)
  {
    Fail(name, line, "delta_phi must be in [0, 180] degrees");
  }
  if (row.Values[3] < 0.0 || row.Values[4] < 0.0 || row.Values[5] < 0.0)
  {
    Fail(name, line, "BRDF values must be >= 0");
  }
  return row;
}

/// The data rows of the CSV text, after its header line (blank lines and # comments skipped);
/// `lastLine` is set to the number of the last line read. Fails without a header or rows.
std::vector<CsvRow> ReadRows(std::istream& in, const std::string& name, int& lastLine)
{
  std::vector<CsvRow> rows;
  std::string text;
  int line = 0;
  lastLine = 1;
  bool headerSeen = false;
  while (std::getline(in, text))
  {
    ++line;
    lastLine = line;
    if (text.find('\0') != std::string::npos)
    {
      Fail(name, line, "NUL byte (a binary file, not a CSV text file?)");
    }
    const std::string trimmed = Trim(text);
    if (trimmed.empty() || trimmed[0] == '#')
    {
      continue;
    }
    if (!headerSeen)
    {
      std::string compact;
      for (const std::string& field : SplitFields(trimmed))
      {
        compact += (compact.empty() ? "" : ",") + field;
      }
      if (compact != Header)
      {
        Fail(name, line, std::string("expected the header '") + Header + "'");
      }
      headerSeen = true;
      continue;
    }
    rows.push_back(ParseRow(trimmed, line, name));
  }
  if (!headerSeen)
  {
    Fail(name, lastLine, std::string("expected the header '") + Header + "'");
  }
  if (rows.empty())
  {
    Fail(name, lastLine, "the table has no rows");
  }
  return rows;
}

/// The distinct values of column `axis` (0 theta_in, 1 theta_out, 2 delta_phi), ascending.
std::vector<double> DistinctValues(const std::vector<CsvRow>& rows, int axis)
{
  std::vector<double> values;
  for (const CsvRow& row : rows)
  {
    values.push_back(row.Values[axis]);
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

/// Every row's grid point in the grid of `axes`, sorted in grid order. The grid's shape is
/// checked from these alone, before the grid is allocated: the distinct values of n scattered
/// rows imply up to n^3 grid points (450 rows: 2.4 GB). Sorted in grid order, equal neighbours
/// are duplicates, and the first gap is the first missing point.
std::vector<GridEntry> SortedGridEntries(const std::vector<CsvRow>& rows,
  const std::array<const std::vector<double>*, 3>& axes)
{
  auto indexOf = [](const std::vector<double>& axis, double v) {
    return static_cast<std::size_t>(std::lower_bound(axis.begin(), axis.end(), v) - axis.begin());
  };
  std::vector<GridEntry> entries(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    entries[r] = { { indexOf(*axes[0], rows[r].Values[0]),
                     indexOf(*axes[1], rows[r].Values[1]),
                     indexOf(*axes[2], rows[r].Values[2]) },
      r };
  }
  std::stable_sort(entries.begin(),
    entries.end(),
    [](const GridEntry& x, const GridEntry& y) { return x.Cell < y.Cell; });
  return entries;
}

/// Fails at the first row, in file order, that repeats an earlier one's grid point.
void CheckNoDuplicates(const std::vector<GridEntry>& entries,
  const std::vector<CsvRow>& rows,
  const std::string& name)
{
  // The stable sort keeps equal cells in file order, so the earlier row starts the run.
  std::size_t repeat = 0;
  std::size_t original = 0;
  for (std::size_t e = 1, runStart = 0; e < entries.size(); ++e)
  {
    if (entries[e].Cell != entries[runStart].Cell)
    {
      runStart = e;
    }
    else if (repeat == 0 || entries[e].Row < entries[repeat].Row)
    {
      repeat = e;
      original = runStart;
    }
  }
  if (repeat != 0)
  {
    Fail(name,
      rows[entries[repeat].Row].Line,
      "duplicate grid point (first given on line " +
        std::to_string(rows[entries[original].Row].Line) + ")");
  }
}

/// Fails at the first missing grid point unless the rows (without duplicates) fill the grid.
void CheckComplete(const std::vector<GridEntry>& entries,
  const std::array<const std::vector<double>*, 3>& axes,
  int lastLine,
  const std::string& name)
{
  const std::size_t nIn = axes[0]->size();
  const std::size_t nOut = axes[1]->size();
  const std::size_t nPhi = axes[2]->size();
  const std::size_t rows = entries.size();
  // Without duplicates the rows fill the grid exactly when their number is nIn * nOut * nPhi
  // (compared without forming a product that could overflow).
  if (nOut * nPhi > rows || nIn > rows / (nOut * nPhi) || nIn * nOut * nPhi != rows)
  {
    std::array<std::size_t, 3> cell = { 0, 0, 0 }; // the next grid point, in grid order
    for (std::size_t e = 0; e < entries.size() && entries[e].Cell == cell; ++e)
    {
      if (++cell[2] == nPhi)
      {
        cell[2] = 0;
        if (++cell[1] == nOut)
        {
          cell[1] = 0;
          ++cell[0];
        }
      }
    }
    std::ostringstream problem;
    problem << "missing grid point theta_in = " << (*axes[0])[cell[0]]
            << ", theta_out = " << (*axes[1])[cell[1]] << ", delta_phi = " << (*axes[2])[cell[2]]
            << " (the rows must give every combination of the listed angles: " << nIn << " x "
            << nOut << " x " << nPhi << " values, " << rows << " rows)";
    Fail(name, lastLine, problem.str());
  }
}

/// Energy conservation: no direction may reflect more than it receives. Checked at the listed
/// theta_out values and every degree in between.
void CheckAlbedo(const BrdfTable& table, const std::string& name)
{
  for (int degree = 0; degree <= 90; ++degree)
  {
    const glm::dvec3 albedo = table.Albedo(degree * Degree);
    for (int band = 0; band < 3; ++band)
    {
      if (albedo[band] > 1.0 + 1e-6)
      {
        std::ostringstream problem;
        problem << "directional albedo " << albedo[band] << " exceeds 1 at theta_out = " << degree
                << " degrees in band " << band
                << " (the surface would reflect more than it receives)";
        Fail(name, 0, problem.str());
      }
    }
  }
}
}

BrdfTable BrdfTable::Parse(std::istream& in, const std::string& displayName)
{
  int lastLine = 1;
  const std::vector<CsvRow> rows = ReadRows(in, displayName, lastLine);
  // The grid: the distinct values of each angle, and every combination exactly once.
  BrdfTable table;
  table.ThetaInValues = DistinctValues(rows, 0);
  table.ThetaOutValues = DistinctValues(rows, 1);
  table.DeltaPhiValues = DistinctValues(rows, 2);
  const std::array<const std::vector<double>*, 3> axes = {
    &table.ThetaInValues, &table.ThetaOutValues, &table.DeltaPhiValues
  };
  const std::vector<GridEntry> entries = SortedGridEntries(rows, axes);
  CheckNoDuplicates(entries, rows, displayName);
  CheckComplete(entries, axes, lastLine, displayName);
  const std::size_t nOut = table.ThetaOutValues.size();
  const std::size_t nPhi = table.DeltaPhiValues.size();
  table.Values.resize(rows.size());
  for (const GridEntry& entry : entries)
  {
    const CsvRow& row = rows[entry.Row];
    table.Values[(entry.Cell[0] * nOut + entry.Cell[1]) * nPhi + entry.Cell[2]] =
      glm::dvec3(row.Values[3], row.Values[4], row.Values[5]);
  }
  for (std::vector<double>* axis :
    { &table.ThetaInValues, &table.ThetaOutValues, &table.DeltaPhiValues })
  {
    for (double& value : *axis)
    {
      value *= Degree;
    }
  }
  CheckAlbedo(table, displayName);
  return table;
}

BrdfTable BrdfTable::Load(const std::string& path)
{
  std::ifstream in = OpenInputFile(path);
  return Parse(in, path);
}

glm::dvec3 BrdfTable::Evaluate(double thetaIn, double thetaOut, double deltaPhi) const
{
  // Fold delta_phi into [0, pi]: f depends on |delta_phi| (isotropic, mirror-symmetric).
  double phi = std::fmod(std::fabs(deltaPhi), 2.0 * Pi);
  if (phi > Pi)
  {
    phi = 2.0 * Pi - phi;
  }
  std::size_t ia = 0, ib = 0, ic = 0;
  double ta = 0.0, tb = 0.0, tc = 0.0;
  Locate(this->ThetaInValues, thetaIn, ia, ta);
  Locate(this->ThetaOutValues, thetaOut, ib, tb);
  Locate(this->DeltaPhiValues, phi, ic, tc);
  const std::size_t na = this->ThetaInValues.size();
  const std::size_t nb = this->ThetaOutValues.size();
  const std::size_t nc = this->DeltaPhiValues.size();
  glm::dvec3 sum(0.0);
  for (int da = 0; da < 2; ++da)
  {
    const double wa = da ? ta : 1.0 - ta;
    const std::size_t a = std::min(ia + da, na - 1);
    for (int db = 0; db < 2; ++db)
    {
      const double wb = db ? tb : 1.0 - tb;
      const std::size_t b = std::min(ib + db, nb - 1);
      for (int dc = 0; dc < 2; ++dc)
      {
        const double wc = dc ? tc : 1.0 - tc;
        const std::size_t c = std::min(ic + dc, nc - 1);
        const double w = wa * wb * wc;
        if (w != 0.0)
        {
          sum += w * this->Values[(a * nb + b) * nc + c];
        }
      }
    }
  }
  return sum;
}

glm::dvec3 BrdfTable::Albedo(double thetaOut, int thetaSteps, int phiSteps) const
{
  // cos(theta) sin(theta) dtheta = d(sin^2 theta) / 2, so the midpoint rule in s = sin^2 theta
  // weighs every step equally: integral = sum f * (1 / thetaSteps) / 2 * (2 pi / phiSteps) * 2
  // over delta_phi in [0, pi] counted twice.
  glm::dvec3 sum(0.0);
  for (int a = 0; a < thetaSteps; ++a)
  {
    const double s = (a + 0.5) / thetaSteps;
    const double thetaIn = std::asin(std::sqrt(s));
    for (int c = 0; c < phiSteps; ++c)
    {
      sum += this->Evaluate(thetaIn, thetaOut, (c + 0.5) * Pi / phiSteps);
    }
  }
  return sum * (Pi / (static_cast<double>(thetaSteps) * phiSteps));
}

} // namespace sphcover
