// The manufacturing deviations files and the stage layout they describe.

#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/geometry/deviations.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace cycloid
{
  namespace geometry
  {
    namespace
    {
      /** One data row of a CSV file: its line and its cells by column. */
      struct Row
      {
        unsigned int                       line = 0;
        std::map<std::string, std::string> cells;
      };

      std::string
      trim(const std::string &s)
      {
        const auto a = s.find_first_not_of(" \t\r");
        const auto b = s.find_last_not_of(" \t\r");
        return a == std::string::npos ? "" : s.substr(a, b - a + 1);
      }

      std::vector<std::string>
      split(const std::string &line)
      {
        std::vector<std::string> cells;
        std::stringstream        in(line);
        std::string              cell;
        while (std::getline(in, cell, ','))
          cells.push_back(trim(cell));
        if (!line.empty() && line.back() == ',')
          cells.emplace_back();
        return cells;
      }

      [[noreturn]] void
      fail(const std::string &what,
           const std::string &file,
           const std::string &message)
      {
        AssertThrow(false,
                    dealii::ExcMessage("Deviations/" + what + " '" + file +
                                       "': " + message));
        std::abort();
      }

      /** The rows of @p file, each with every one of @p columns (the
       * header's names; others are an error). */
      std::vector<Row>
      read_rows(const std::string              &what,
                const std::string              &file,
                const std::vector<std::string> &columns)
      {
        std::ifstream in(file);
        if (!in)
          fail(what, file, "cannot be read (no such file, or no permission).");
        std::string              text;
        std::vector<std::string> header;
        std::vector<Row>         rows;
        for (unsigned int line = 1; std::getline(in, text); ++line)
          {
            const std::string t = trim(text);
            if (t.empty() || t[0] == '#')
              continue;
            const std::vector<std::string> cells = split(t);
            if (header.empty())
              {
                header = cells;
                for (const std::string &c : columns)
                  if (std::find(header.begin(), header.end(), c) ==
                      header.end())
                    fail(what,
                         file,
                         "line " + std::to_string(line) + ": no column '" + c +
                           "' in the header (expected " + columns[0] + ", " +
                           columns[1] + ", ...).");
                for (const std::string &h : header)
                  if (std::find(columns.begin(), columns.end(), h) ==
                      columns.end())
                    fail(what,
                         file,
                         "line " + std::to_string(line) + ": unknown column '" +
                           h + "'.");
                continue;
              }
            if (cells.size() != header.size())
              fail(what,
                   file,
                   "line " + std::to_string(line) + ": " +
                     std::to_string(cells.size()) + " values for " +
                     std::to_string(header.size()) + " columns.");
            Row row;
            row.line = line;
            for (unsigned int k = 0; k < header.size(); ++k)
              row.cells[header[k]] = cells[k];
            rows.push_back(row);
          }
        if (header.empty())
          fail(what, file, "has no header line.");
        return rows;
      }

      /** The number in column @p column of @p row. */
      double
      number(const std::string &what,
             const std::string &file,
             const Row         &row,
             const std::string &column)
      {
        const std::string &text = row.cells.at(column);
        char              *end  = nullptr;
        const double       x    = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(x))
          fail(what,
               file,
               "line " + std::to_string(row.line) + ", column '" + column +
                 "': '" + text + "' is not a number.");
        return x;
      }

      /** The index in column @p column of @p row, below @p n, not seen
       * before (@p seen: index to line). */
      unsigned int
      index(const std::string                    &what,
            const std::string                    &file,
            const Row                            &row,
            const std::string                    &column,
            const unsigned int                    n,
            std::map<unsigned int, unsigned int> &seen)
      {
        const double x = number(what, file, row, column);
        if (x < 0 || x >= n || x != std::floor(x))
          fail(what,
               file,
               "line " + std::to_string(row.line) + ", column '" + column +
                 "': " + row.cells.at(column) + " is not an index from 0 to " +
                 std::to_string(n - 1) + ".");
        const auto k = static_cast<unsigned int>(x);
        if (seen.count(k) > 0)
          fail(what,
               file,
               "line " + std::to_string(row.line) + ", column '" + column +
                 "': " + column + " " + std::to_string(k) +
                 " is listed twice (also on line " + std::to_string(seen[k]) +
                 ").");
        seen[k] = row.line;
        return k;
      }
    } // namespace



    void
    DeviationsParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Deviations");
      prm.declare_entry(
        "Pin deviations file",
        "",
        dealii::Patterns::Anything(),
        "Manufacturing deviations of the pins: a CSV file with the header "
        "pin,radial_um,tangential_um,radius_um (pin j nominally at rp (cos "
        "2 pi j/zp, sin 2 pi j/zp); radial_um moves its centre away from the "
        "housing centre, tangential_um along the counter-clockwise tangent, "
        "radius_um changes its radius; all in um). Pins not listed are as "
        "drawn. A relative path is taken from the parameter file's "
        "directory. Empty: none. Honoured by Run = analytic so far.");
      prm.declare_entry(
        "Disc deviations file",
        "",
        dealii::Patterns::Anything(),
        "Manufacturing deviations of the discs: a CSV file with the header "
        "disc,eccentricity_um,angle_arcmin,pin_circle_um,pin_radius_um (the "
        "disc's centre at e + eccentricity_um along its crank direction, the "
        "profile keeping the shape generated with the nominal e; the disc "
        "turned about its centre by angle_arcmin, counter-clockwise, an "
        "index error of its crank holes; its profile ground with Delta rp + "
        "pin_circle_um and Delta rrp + pin_radius_um). Discs not listed are "
        "as drawn. Empty: none. Honoured by Run = analytic so far.");
      prm.leave_subsection();
    }



    void
    DeviationsParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Deviations");
      pin_file  = trim(prm.get("Pin deviations file"));
      disc_file = trim(prm.get("Disc deviations file"));
      prm.leave_subsection();
    }



    std::string
    DeviationsParameters::resolve(const std::string &file,
                                  const std::string &directory)
    {
      const std::filesystem::path path(file);
      return path.is_absolute() || directory.empty() ?
               file :
               (std::filesystem::path(directory) / path).string();
    }



    void
    DeviationsParameters::read_into(GeometryParameters &geometry,
                                    const std::string  &directory) const
    {
      geometry.pin_deviations.clear();
      geometry.disc_deviations.clear();
      if (!pin_file.empty())
        geometry.pin_deviations =
          read_pin_deviations(resolve(pin_file, directory), geometry.n_pins);
      if (!disc_file.empty())
        geometry.disc_deviations =
          read_disc_deviations(resolve(disc_file, directory));
    }



    void
    check_rest_overlap(const CycloidGeometry      &geo,
                       const std::vector<double>  &angles,
                       const unsigned int          n_discs,
                       const DeviationsParameters &files,
                       const std::string          &directory)
    {
      const GeometryParameters &prm = geo.parameters();
      for (const double psi : angles)
        for (unsigned int d = 0; d < n_discs; ++d)
          for (const PinContact &c : geo.pin_contacts(d, psi))
            {
              if (c.clearance >= -1e-7)
                continue;
              // The line that moved this pin, else the one that placed or
              // ground this disc.
              std::string where;
              for (const PinDeviation &p : prm.pin_deviations)
                if (p.pin == c.pin)
                  where =
                    "Deviations/Pin deviations file '" +
                    DeviationsParameters::resolve(files.pin_file, directory) +
                    "', line " + std::to_string(p.line) + " (pin " +
                    std::to_string(c.pin) + ")";
              for (const DiscDeviation &q : prm.disc_deviations)
                if (where.empty() && q.disc == d)
                  where =
                    "Deviations/Disc deviations file '" +
                    DeviationsParameters::resolve(files.disc_file, directory) +
                    "', line " + std::to_string(q.line) + " (disc " +
                    std::to_string(d) + ")";
              if (where.empty())
                continue; // not a deviation's doing: the geometry says so
              std::ostringstream msg;
              msg << where << ": pin " << c.pin << " overlaps disc " << d
                  << " by " << -c.clearance * 1e3 << " um at rest at crank "
                  << "angle " << psi * 180. / dealii::numbers::PI
                  << " deg; a stage cannot start from a negative clearance.";
              AssertThrow(false, dealii::ExcMessage(msg.str()));
            }
    }



    std::vector<PinDeviation>
    read_pin_deviations(const std::string &file, const unsigned int n_pins)
    {
      const std::string                    what = "Pin deviations file";
      std::vector<PinDeviation>            result;
      std::map<unsigned int, unsigned int> seen;
      for (const Row &row : read_rows(
             what, file, {"pin", "radial_um", "tangential_um", "radius_um"}))
        {
          PinDeviation p;
          p.line          = row.line;
          p.pin           = index(what, file, row, "pin", n_pins, seen);
          p.radial_um     = number(what, file, row, "radial_um");
          p.tangential_um = number(what, file, row, "tangential_um");
          p.radius_um     = number(what, file, row, "radius_um");
          result.push_back(p);
        }
      return result;
    }



    std::vector<DiscDeviation>
    read_disc_deviations(const std::string &file)
    {
      const std::string                    what = "Disc deviations file";
      std::vector<DiscDeviation>           result;
      std::map<unsigned int, unsigned int> seen;
      for (const Row &row : read_rows(what,
                                      file,
                                      {"disc",
                                       "eccentricity_um",
                                       "angle_arcmin",
                                       "pin_circle_um",
                                       "pin_radius_um"}))
        {
          DiscDeviation d;
          d.line = row.line;
          d.disc = index(what, file, row, "disc", StageLayout::n_discs, seen);
          d.eccentricity_um = number(what, file, row, "eccentricity_um");
          d.angle_arcmin    = number(what, file, row, "angle_arcmin");
          d.pin_circle_um   = number(what, file, row, "pin_circle_um");
          d.pin_radius_um   = number(what, file, row, "pin_radius_um");
          result.push_back(d);
        }
      return result;
    }



    StageLayout
    deviated_layout(const GeometryParameters         &prm,
                    const std::vector<PinDeviation>  &pins,
                    const std::vector<DiscDeviation> &discs)
    {
      constexpr double pi     = dealii::numbers::PI;
      constexpr double mm     = 1e-3; // per um
      StageLayout      layout = StageLayout::nominal(prm);
      for (const PinDeviation &p : pins)
        {
          PinData                   &pin = layout.pins.at(p.pin);
          const double               a   = 2. * pi * p.pin / prm.n_pins;
          const dealii::Tensor<1, 2> radial({std::cos(a), std::sin(a)});
          const dealii::Tensor<1, 2> tangent({-std::sin(a), std::cos(a)});
          // Added only where the file moves it, so that a zero row keeps
          // the nominal value's every bit.
          if (p.radial_um != 0 || p.tangential_um != 0)
            pin.centre +=
              (p.radial_um * mm) * radial + (p.tangential_um * mm) * tangent;
          if (p.radius_um != 0)
            pin.radius += p.radius_um * mm;
        }
      for (const DiscDeviation &d : discs)
        {
          DiscData &disc = layout.discs.at(d.disc);
          if (d.eccentricity_um != 0)
            disc.eccentricity += d.eccentricity_um * mm;
          if (d.angle_arcmin != 0)
            disc.index_angle += d.angle_arcmin * pi / (180. * 60.);
          if (d.pin_circle_um != 0)
            disc.delta_pin_circle_radius += d.pin_circle_um * mm;
          if (d.pin_radius_um != 0)
            disc.delta_pin_radius += d.pin_radius_um * mm;
        }
      return layout;
    }
  } // namespace geometry
} // namespace cycloid
