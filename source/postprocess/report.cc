#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cycloid/postprocess/columns.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/postprocess/sweep_noise.h>
#include <cycloid/results/error_estimate.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace cycloid
{
  namespace postprocess
  {
    namespace u = results::units;

    namespace
    {
      /** @p x as a percentage with two significant digits. */
      std::string
      pct(const double x)
      {
        std::ostringstream out;
        out << std::setprecision(2) << 100. * x << " %";
        return out.str();
      }
    } // namespace

    std::string
    Report::stiffness_header()
    {
      return header(stiffness_columns());
    }



    std::string
    Report::pin_forces_header()
    {
      return header(pin_force_columns());
    }



    std::string
    Report::energy_header()
    {
      return header(energy_columns());
    }



    std::string
    Report::torsion_curve_header()
    {
      return "torque_Nm,rotation_rad,rotation_arcmin,crank_deg,step,"
             "takeup_rad";
    }



    std::string
    Report::rigidity_header()
    {
      return "torsional_rigidity_Nm_per_arcmin,lost_motion_arcmin,"
             "backlash_arcmin,rated_torque_Nm,crank_deg,"
             "lost_motion_clearance_arcmin,lost_motion_elastic_arcmin";
    }



    Statistics::Statistics(const std::vector<double> &values)
    {
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      for (const double x : values)
        mean += x;
      mean /= values.size();
      min         = *lo;
      max         = *hi;
      fluctuation = (max - min) / mean;
    }



    Report::Report(const Options &options, const MPI_Comm comm)
      : options(options)
      , active(dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    {
      if (!active)
        return;
      const auto names = files();
      AssertThrow(!options.resume ||
                    options.resume_sizes.size() == names.size(),
                  dealii::ExcInternalError());
      std::vector<std::ofstream *> streams{&stiffness, &pin_forces};
      std::vector<std::string> headers{stiffness_header(), pin_forces_header()};
      if (options.energy)
        {
          streams.push_back(&energy);
          headers.push_back(energy_header());
        }
      if (options.bearings)
        {
          streams.push_back(&bearing_forces);
          headers.push_back(header(bearing_columns()));
        }
      if (options.breakdown)
        {
          streams.push_back(&breakdown);
          headers.push_back(header(breakdown_columns()));
        }
      for (unsigned int i = 0; i < names.size(); ++i)
        {
          const std::string file = options.directory + "/" + names[i];
          if (options.resume)
            {
              // A restart continues from the checkpoint: rows written after
              // it are dropped.
              std::error_code ec;
              AssertThrow(std::filesystem::file_size(file, ec) >=
                              options.resume_sizes[i] &&
                            !ec,
                          dealii::ExcMessage(
                            "Transient/Resume: " + file +
                            " is missing or shorter than at the checkpoint."));
              std::filesystem::resize_file(file, options.resume_sizes[i]);
              streams[i]->open(file, std::ios::app);
            }
          else
            streams[i]->open(file);
          AssertThrow(*streams[i],
                      dealii::ExcMessage("cannot write to Output directory '" +
                                         options.directory + "'."));
          *streams[i] << std::setprecision(12);
          if (!options.resume)
            *streams[i] << headers[i] << std::endl;
        }
    }



    std::vector<std::string>
    Report::files() const
    {
      std::vector<std::string> names{"stiffness.csv", "pin_forces.csv"};
      if (options.energy)
        names.emplace_back("energy.csv");
      if (options.bearings)
        names.emplace_back("bearing_forces.csv");
      if (options.breakdown)
        names.emplace_back("compliance_breakdown.csv");
      return names;
    }



    std::vector<std::uintmax_t>
    Report::file_sizes() const
    {
      std::vector<std::uintmax_t> sizes;
      for (const auto &name : files())
        {
          std::error_code ec;
          const auto      n =
            std::filesystem::file_size(options.directory + "/" + name, ec);
          sizes.push_back(ec ? 0 : n);
        }
      return sizes;
    }



    void
    Report::write(const results::StageState &s, const double load)
    {
      if (!active)
        return;
      write_row(stiffness,
                stiffness_columns(),
                StiffnessRow{s, flag(s), max_pin_hertz_nodes(s)});
      ++n_written;
      if (flag(s))
        ++n_flagged;
      for (const results::PinState &p : s.pins)
        write_row(pin_forces, pin_force_columns(), PinRow{s, p});
      stiffness.flush();
      pin_forces.flush();
      if (options.bearings)
        {
          for (const results::BearingState &b : s.bearings)
            write_row(bearing_forces, bearing_columns(), BearingRow{s, b});
          bearing_forces.flush();
        }
      if (options.breakdown)
        {
          write_row(breakdown, breakdown_columns(), s);
          breakdown.flush();
        }

      auto it = std::find_if(series.begin(),
                             series.end(),
                             [&](const Series &x) { return x.load == load; });
      if (it == series.end())
        {
          series.push_back(Series{load, {}, {}, {}, {}});
          it = std::prev(series.end());
        }
      // A load met again at the same crank angle (a torque cycle passes
      // each torque twice) adds no point to the series over the period.
      if (it->crank.empty() || it->crank.back() != s.crank)
        {
          it->crank.push_back(s.crank);
          it->k_tangent.push_back(s.k_tangent);
          it->k_secant.push_back(s.k_secant());
          it->rotation.push_back(s.rotation);
        }
      if (options.torque_cycle)
        cycle.push_back({s.crank, s.torque, s.rotation, s.takeup});
      for (const results::PinState &p : s.pins)
        {
          if (p.fn > peak.pin.fn)
            peak = {s.step, s.crank, s.torque, p};
          if (p.max_pressure > peak_pressure.pin.max_pressure)
            peak_pressure = {s.step, s.crank, s.torque, p};
        }
      const auto highest = s.highest_pressure_pin();
      if (options.allowable_pressure > 0 && highest != s.pins.end() &&
          highest->max_pressure > options.allowable_pressure)
        ++n_overloaded;
    }



    void
    Report::write(const results::EnergyState &e, const results::StageState &s)
    {
      if (!active)
        return;
      write_row(energy, energy_columns(), EnergyRow{e, s});
      energy.flush();
    }



    void
    Report::print(const results::StageState &s, const std::string &prefix) const
    {
      if (!active)
        return;
      std::cout << prefix << "T " << s.torque << " N m, beta " << s.rotation
                << " rad, K_secant " << s.k_secant() << ", K_tangent "
                << s.k_tangent << " N m/rad ("
                << s.k_tangent * u::rad_per_arcmin << " N m/arcmin), pins "
                << s.pins_in_contact() << ", iterations " << s.iterations;
      const auto most    = s.most_loaded_pin();
      const auto highest = s.highest_pressure_pin();
      if (most != s.pins.end() && most->fn > 0)
        std::cout << ", max Fn " << most->fn << " N (disc " << most->disc
                  << " pin " << most->pin << "), peak contact pressure "
                  << highest->max_pressure << " MPa (disc " << highest->disc
                  << " pin " << highest->pin << ")";
      if (!s.bearings.empty() && s.rotation != 0)
        {
          double peak = 0;
          for (const results::BearingState &b : s.bearings)
            peak = std::max(peak, std::hypot(b.fx, b.fy));
          std::cout << ", crank bearings "
                    << 100. * s.breakdown.bearings / s.rotation
                    << " % of beta, largest bearing force " << peak << " N";
        }
      if (s.dofs > 0)
        std::cout << ", dofs " << s.dofs;
      std::cout << ", " << s.wall_s << " s" << std::endl;
      if (s.cycles_broken > 0)
        std::cout << "    note: the active set cycled; the union of the "
                     "cycle's sets was taken (largest tension left "
                  << s.cycle_tension
                  << " of the largest nodal force; doc/stability.md, "
                     "\"Active-set cycling\")"
                  << std::endl;
      print_estimate(s);
    }



    bool
    Report::flag(const results::StageState &s) const
    {
      if (options.warning_threshold <= 0)
        return false;
      if (!s.error.failure.empty())
        return true;
      // The estimate from nested levels, where there is one, is the
      // better figure; the resolution indicator stands in where not.
      if (s.error.available())
        return s.error.largest() > options.warning_threshold;
      return results::resolution_error(s) > options.warning_threshold;
    }



    double
    Report::max_pin_hertz_nodes(const results::StageState &s)
    {
      const auto most = s.most_loaded_pin();
      return most == s.pins.end() ? std::numeric_limits<double>::quiet_NaN() :
                                    most->hertz_nodes;
    }



    void
    Report::print_estimate(const results::StageState &s) const
    {
      if (!s.error.failure.empty())
        std::cout << "    WARNING: no error estimate: the next coarser "
                  << (s.error.method.empty() ? "contact level" : "model")
                  << " failed (" << s.error.failure
                  << "); the mesh is near the coarsest the solver "
                  << "resolves. " << options.refine_advice << std::endl;
      if (!s.error.available())
        return print_resolution(s);
      std::cout << "    estimated error ("
                << (s.error.method.empty() ?
                      "contact levels " +
                        std::to_string(s.error.contact_level - 2) + " to " +
                        std::to_string(s.error.contact_level) :
                      s.error.method)
                << "): K_secant " << pct(s.error.k_secant) << ", K_tangent "
                << pct(s.error.k_tangent) << ", pin forces "
                << pct(s.error.max_pin_force) << " of the largest";
      if (!std::isnan(s.error.bulk))
        std::cout << "; of these the bulk mesh's part up to "
                  << pct(s.error.bulk);
      if (!std::isnan(s.error.model))
        std::cout << "; of these the near-field law's own "
                  << pct(s.error.model) << " (5 (a/R)^2)";
      std::cout << std::endl;
      if (!flag(s))
        return;
      std::cout << "    WARNING: the estimate exceeds Mesh/Warning threshold ("
                << pct(options.warning_threshold) << "): this state's mesh "
                << "does not resolve the contacts";
      const auto pins = results::unresolved_pins(s, options.warning_threshold);
      for (unsigned int i = 0; i < pins.size(); ++i)
        std::cout << (i == 0 ? "; pin forces off by up to: " : ", ") << pins[i];
      std::cout << ". " << options.refine_advice << std::endl;
      if (s.error.bulk > 0.5 * options.warning_threshold)
        std::cout << "    The bulk mesh's part (" << pct(s.error.bulk)
                  << ") is not reduced by contact refinements: "
                  << results::bulk_advice << std::endl;
    }



    void
    Report::print_resolution(const results::StageState &s) const
    {
      const double e = results::resolution_error(s);
      if (!(e > 0))
        return;
      const auto   most    = s.most_loaded_pin();
      const double n       = most->hertz_nodes;
      const double spacing = 2. * most->hertz_halfwidth / n;
      std::cout << "    contact resolution: " << std::setprecision(2) << n
                << " node(s) across the Hertz width of the most loaded pin ("
                << std::lround(2. * most->hertz_halfwidth * u::um_per_mm)
                << " um, nodes " << std::lround(spacing * u::um_per_mm)
                << " um apart): pin forces to about " << pct(e)
                << " of the largest (no estimate from nested levels)"
                << std::setprecision(6) << std::endl;
      if (!flag(s))
        return;
      // Each contact refinement halves the spacing: n doubles and the
      // indicator falls by 4.
      const int levels = static_cast<int>(
        std::ceil(std::log(e / options.warning_threshold) / std::log(4.)));
      std::cout << "    WARNING: the contact resolution exceeds Mesh/Warning "
                << "threshold (" << pct(options.warning_threshold)
                << "): this state's mesh does not resolve the contact of "
                << "disc " << most->disc << " pin " << most->pin << " (about "
                << levels << " more contact refinement level(s) would). "
                << options.refine_advice << std::endl;
    }



    void
    Report::write_fluctuation() const
    {
      std::ofstream out(options.directory + "/fluctuation.csv");
      out << (options.rotation_control ? "rotation_rad" : "torque_Nm")
          << ",n_phases,K_tangent_mean_Nm_per_rad,"
             "K_tangent_min_Nm_per_rad,K_tangent_max_Nm_per_rad,"
             "K_tangent_fluctuation,K_secant_mean_Nm_per_rad,"
             "K_secant_fluctuation,K_tangent_period_closure,"
             "transmission_error_mean_arcsec,transmission_error_pp_arcsec,"
             "K_tangent_noise_floor,K_tangent_fluctuation_resolved,"
             "K_tangent_refinement_change\n"
          << std::setprecision(12);
      for (unsigned int i = 0; i < series.size(); ++i)
        {
          const Series &x = series[i];
          // A torque cycle's zero torque has no stiffness (the states are
          // the ends of the clearance).
          if (options.torque_cycle && x.load == 0)
            continue;
          const Statistics kt(x.k_tangent), ks(x.k_secant), te(x.rotation);
          // The first and last phase are one mesh period apart: their
          // ratio shows how far the discretisation is from periodic.
          const double closure = x.k_tangent.back() / x.k_tangent.front() - 1;
          // Transmission error: the loaded output rotation's deviation from
          // the kinematic one, which is beta itself.
          const double te_mean = te.mean * u::arcsec_per_rad,
                       te_pp   = (te.max - te.min) * u::arcsec_per_rad;
          SweepNoise noise     = this->noise(i);
          if (!options.discretised)
            {
              // No mesh, no mesh noise (the closure of an analytic sweep
              // is the crank holes' physical lack of periodicity).
              noise.floor    = 0;
              noise.resolved = true;
            }
          out << x.load << ',' << x.crank.size() << ',' << kt.mean << ','
              << kt.min << ',' << kt.max << ',' << kt.fluctuation << ','
              << ks.mean << ',' << ks.fluctuation << ',' << closure << ','
              << te_mean << ',' << te_pp << ',' << noise.floor << ','
              << (noise.resolved ? 1 : 0) << ',' << noise.refinement << '\n';
          std::cout << "  "
                    << (options.rotation_control ? "rotation " : "torque ")
                    << x.load << (options.rotation_control ? " rad" : " N m")
                    << ": K_tangent over the period mean " << kt.mean
                    << ", min " << kt.min << ", max " << kt.max
                    << " N m/rad; fluctuation (max-min)/mean " << kt.fluctuation
                    << "; first vs last phase " << closure
                    << "; transmission error mean " << te_mean
                    << " arcsec, peak-to-peak " << te_pp << " arcsec"
                    << std::endl;
          if (options.discretised)
            print_noise(noise);
        }
    }



    double
    Report::noise_ratio() const
    {
      double ratio = 0;
      if (!active || !options.discretised)
        return ratio;
      for (unsigned int i = 0; i < series.size(); ++i)
        {
          const Series &x = series[i];
          if ((options.torque_cycle && x.load == 0) || x.crank.size() < 2)
            continue;
          const SweepNoise noise = this->noise(i);
          if (std::isnan(noise.floor))
            return std::numeric_limits<double>::quiet_NaN();
          // A fluctuation of exactly zero with a zero floor is resolved
          // (nothing varies, nothing is noise).
          if (noise.floor > 0)
            ratio = std::max(ratio,
                             noise.fluctuation > 0 ?
                               noise.floor / noise.fluctuation :
                               std::numeric_limits<double>::infinity());
        }
      return ratio;
    }



    SweepNoise
    Report::noise(const unsigned int i) const
    {
      const auto &c = options.coarser_k_tangent;
      return sweep_noise(series[i].k_tangent,
                         i < c.size() ? c[i] : std::vector<double>());
    }



    std::vector<std::vector<double>>
    Report::k_tangent_series() const
    {
      std::vector<std::vector<double>> k;
      for (const Series &x : series)
        k.push_back(x.k_tangent);
      return k;
    }



    void
    Report::print_noise(const SweepNoise &noise) const
    {
      const std::string source =
        std::isnan(noise.refinement) ?
          "first vs last phase, phase-to-phase roughness" :
          "first vs last phase, the change since the coarser pass";
      if (noise.resolved)
        std::cout << "    the fluctuation is resolved: above twice the "
                     "noise floor "
                  << noise.floor << " (" << source
                  << "; doc/user-guide.md, fluctuation.csv)" << std::endl;
      else if (std::isnan(noise.floor))
        std::cout << "    warning: the mesh noise floor of this sweep is "
                     "unknown (fewer than 5 phases and the first and last "
                     "phase on the same mesh): use Loading/Number of phases "
                     ">= 9 before reading the fluctuation as physical"
                  << std::endl;
      else
        std::cout << "    warning: the fluctuation " << noise.fluctuation
                  << " is not resolved: it is below twice the noise floor "
                  << noise.floor
                  << " that mesh-to-mesh differences alone produce (" << source
                  << (options.sweep_target ?
                        "); the sweep's target accuracy decides below "
                        "whether to repeat it finer" :
                        "); refine the contact mesh (Mesh/Contact "
                        "refinements), take more phases, or set Mesh/Target "
                        "accuracy (the sweep is then repeated finer and the "
                        "change measured) before reading it as the stage's")
                  << std::endl;
    }



    void
    Report::write_torque_cycle() const
    {
      std::ofstream curve(options.directory + "/torsion_curve.csv");
      std::ofstream rigidity(options.directory + "/rigidity.csv");
      curve << torsion_curve_header() << '\n' << std::setprecision(12);
      rigidity << rigidity_header() << '\n' << std::setprecision(12);
      std::vector<TorsionPoint> one; // the states of one crank angle
      for (unsigned int i = 0; i < cycle.size(); ++i)
        {
          const TorsionPoint &p = cycle[i];
          curve << p.torque + 0. << ',' << p.rotation + 0. << ','
                << p.rotation * u::arcmin_per_rad + 0. << ','
                << p.crank * u::deg_per_rad << ',' << i << ',' << p.takeup + 0.
                << '\n';
          one.push_back(p);
          if (i + 1 < cycle.size() && cycle[i + 1].crank == p.crank)
            continue;
          const CatalogueFigures c =
            catalogue_figures(one,
                              options.rated_torque,
                              options.lost_motion_fraction);
          rigidity << c.rigidity_Nm_per_arcmin << ',' << c.lost_motion_arcmin
                   << ',' << c.backlash_arcmin << ',' << c.rated_torque << ','
                   << c.crank * u::deg_per_rad << ','
                   << c.lost_motion_clearance_arcmin << ','
                   << c.lost_motion_elastic_arcmin << '\n';
          std::cout << (options.bearings ?
                          "  catalogue figures of the cycloid-pin stage on "
                          "its crank needle bearings (no shafts, main "
                          "bearings or carrier), crank " :
                          "  catalogue figures of the cycloid-pin stage alone "
                          "(no bearings or shafts), crank ")
                    << c.crank * u::deg_per_rad << " deg, rated torque "
                    << c.rated_torque << " N m: torsional rigidity "
                    << c.rigidity_Nm_per_arcmin << " N m/arcmin, lost motion "
                    << c.lost_motion_arcmin << " arcmin (clearance "
                    << c.lost_motion_clearance_arcmin << ", elastic "
                    << c.lost_motion_elastic_arcmin << "), backlash "
                    << c.backlash_arcmin << " arcmin" << std::endl;
          one.clear();
        }
    }



    void
    Report::finish() const
    {
      if (!active)
        return;
      std::string written;
      for (const std::string &name : files())
        written += (written.empty() ? "" : ", ") + name;
      if (options.bearings)
        std::cout << "  crank bearings: the rotation, rigidity and lost "
                     "motion are the cycloid stage's on its crank needle "
                     "bearings, the eccentrics rigid; the crankshafts, their "
                     "main bearings and the output carrier are not in them "
                     "(doc/bearings.md)"
                  << std::endl;
      if (options.fluctuation && !series.empty() &&
          series.front().crank.size() > 1)
        {
          write_fluctuation();
          written += ", fluctuation.csv";
        }
      if (options.torque_cycle && !cycle.empty())
        {
          write_torque_cycle();
          written += ", torsion_curve.csv, rigidity.csv";
        }
      print_peaks();
      if (n_flagged > 0)
        std::cout << "  WARNING: " << n_flagged << " of " << n_written
                  << " state(s) exceed Mesh/Warning threshold ("
                  << options.warning_threshold
                  << ") in their error estimate or, without one, their "
                  << "contact resolution (stiffness.csv mesh_warning = 1). "
                  << options.refine_advice << std::endl;
      std::cout << "  results in " << options.directory << "/: " << written
                << std::endl;
    }



    void
    Report::print_peaks() const
    {
      if (!(peak.pin.fn > 0))
        return;
      const auto where = [](const PeakPin &p) {
        std::ostringstream s;
        s << "disc " << p.pin.disc << ", pin " << p.pin.pin << " (state "
          << p.step + 1 << ", crank " << p.crank * u::deg_per_rad
          << " deg, torque " << p.torque << " N m)";
        return s.str();
      };
      std::cout << "  most loaded pin: " << where(peak) << ", Fn "
                << peak.pin.fn << " N, its peak contact pressure "
                << peak.pin.max_pressure << " MPa" << std::endl;
      std::cout << "  highest contact pressure: "
                << peak_pressure.pin.max_pressure << " MPa, "
                << where(peak_pressure) << ", Fn " << peak_pressure.pin.fn
                << " N" << std::endl;
      if (n_overloaded > 0)
        std::cout << "  warning: the peak contact pressure "
                  << peak_pressure.pin.max_pressure << " MPa on "
                  << where(peak_pressure)
                  << " exceeds Material/Allowable contact pressure ("
                  << options.allowable_pressure << " MPa), in " << n_overloaded
                  << " of " << n_written
                  << " state(s): the contact would pit or yield; check the "
                     "Torque, or raise the entry for a stronger material"
                  << std::endl;
    }
  } // namespace postprocess
} // namespace cycloid
