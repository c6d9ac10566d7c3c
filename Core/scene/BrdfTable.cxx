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
}

BrdfTable BrdfTable::Parse(std::istream& in, const std::string& displayName)
{
  auto fail = [&](int line, const std::string& problem)
  { throw InputError(displayName, line > 0 ? "line " + std::to_string(line) : "", problem); };

  struct Row
  {
    double Values[6];
    int Line;
  };
  std::vector<Row> rows;
  std::string text;
  int line = 0;
  int lastLine = 1;
  bool headerSeen = false;
  while (std::getline(in, text))
  {
    ++line;
    lastLine = line;
    if (text.find('\0') != std::string::npos)
    {
      fail(line, "NUL byte (a binary file, not a CSV text file?)");
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
        fail(line, std::string("expected the header '") + Header + "'");
      }
      headerSeen = true;
      continue;
    }
    const std::vector<std::string> fields = SplitFields(trimmed);
    if (fields.size() != 6)
    {
      fail(line, "expected 6 comma-separated numbers, got " + std::to_string(fields.size()));
    }
    Row row{};
    row.Line = line;
    for (int k = 0; k < 6; ++k)
    {
      const std::string& field = fields[static_cast<std::size_t>(k)];
      char* end = nullptr;
      const double value = field.empty() ? 0.0 : std::strtod(field.c_str(), &end);
      if (field.empty() || end != field.c_str() + field.size())
      {
        fail(line, "expected a number in column " + std::to_string(k + 1));
      }
      // strtod's ERANGE also flags underflow (1e-310 is subnormal, 1e-400 rounds to 0): such
      // values are harmless and read as rounded; only overflow and nan/inf are errors.
      if (!std::isfinite(value))
      {
        fail(line, "not a finite number in column " + std::to_string(k + 1));
      }
      row.Values[k] = value;
    }
    if (row.Values[0] < 0.0 || row.Values[0] > 90.0 || row.Values[1] < 0.0 || row.Values[1] > 90.0)
    {
      fail(line, "theta_in and theta_out must be in [0, 90] degrees");
    }
    if (row.Values[2] < 0.0 || row.Values[2] > 180.0)
    {
      fail(line, "delta_phi must be in [0, 180] degrees");
    }
    if (row.Values[3] < 0.0 || row.Values[4] < 0.0 || row.Values[5] < 0.0)
    {
      fail(line, "BRDF values must be >= 0");
    }
    rows.push_back(row);
  }
  if (!headerSeen)
  {
    fail(lastLine, std::string("expected the header '") + Header + "'");
  }
  if (rows.empty())
  {
    fail(lastLine, "the table has no rows");
  }

  // The grid: the distinct values of each angle, and every combination exactly once.
  BrdfTable table;
  std::vector<double>* axes[3] = {
    &table.ThetaInValues, &table.ThetaOutValues, &table.DeltaPhiValues
  };
  for (int a = 0; a < 3; ++a)
  {
    for (const Row& row : rows)
    {
      axes[a]->push_back(row.Values[a]);
    }
    std::sort(axes[a]->begin(), axes[a]->end());
    axes[a]->erase(std::unique(axes[a]->begin(), axes[a]->end()), axes[a]->end());
  }
  const std::size_t nIn = table.ThetaInValues.size();
  const std::size_t nOut = table.ThetaOutValues.size();
  const std::size_t nPhi = table.DeltaPhiValues.size();
  auto indexOf = [](const std::vector<double>& axis, double v) {
    return static_cast<std::size_t>(std::lower_bound(axis.begin(), axis.end(), v) - axis.begin());
  };
  // The grid's shape is checked from the rows alone, before the grid is allocated: the
  // distinct values of n scattered rows imply up to n^3 grid points (450 rows: 2.4 GB).
  // Sorted in grid order, equal neighbours are duplicates, and the first gap is the first
  // missing point.
  struct Entry
  {
    std::array<std::size_t, 3> Cell;
    std::size_t Row;
  };
  std::vector<Entry> entries(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    entries[r] = { { indexOf(table.ThetaInValues, rows[r].Values[0]),
                     indexOf(table.ThetaOutValues, rows[r].Values[1]),
                     indexOf(table.DeltaPhiValues, rows[r].Values[2]) },
      r };
  }
  std::stable_sort(
    entries.begin(), entries.end(), [](const Entry& x, const Entry& y) { return x.Cell < y.Cell; });
  // The duplicate reported is the first row, in file order, that repeats an earlier one; the
  // stable sort keeps equal cells in file order, so that earlier one starts the run.
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
    fail(rows[entries[repeat].Row].Line,
      "duplicate grid point (first given on line " +
        std::to_string(rows[entries[original].Row].Line) + ")");
  }
  // Without duplicates the rows fill the grid exactly when their number is nIn * nOut * nPhi
  // (compared without forming a product that could overflow).
  if (nOut * nPhi > rows.size() || nIn > rows.size() / (nOut * nPhi) ||
    nIn * nOut * nPhi != rows.size())
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
    problem << "missing grid point theta_in = " << table.ThetaInValues[cell[0]]
            << ", theta_out = " << table.ThetaOutValues[cell[1]]
            << ", delta_phi = " << table.DeltaPhiValues[cell[2]]
            << " (the rows must give every combination of the listed angles: " << nIn << " x "
            << nOut << " x " << nPhi << " values, " << rows.size() << " rows)";
    fail(lastLine, problem.str());
  }
  table.Values.resize(rows.size());
  for (const Entry& entry : entries)
  {
    const Row& row = rows[entry.Row];
    table.Values[(entry.Cell[0] * nOut + entry.Cell[1]) * nPhi + entry.Cell[2]] =
      glm::dvec3(row.Values[3], row.Values[4], row.Values[5]);
  }
  for (int a = 0; a < 3; ++a)
  {
    for (double& value : *axes[a])
    {
      value *= Degree;
    }
  }
  // Energy conservation: no direction may reflect more than it receives. Checked at the
  // listed theta_out values and every degree in between.
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
        fail(0, problem.str());
      }
    }
  }
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
