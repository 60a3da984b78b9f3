#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cycloid/analytic/stage_model.h>
#include <cycloid/postprocess/catalogue.h>
#include <cycloid/postprocess/columns.h>
#include <cycloid/results/cost_figures.h>
#include <cycloid/runs/tolerance_run.h>
#include <cycloid/stage/stage_scene.h>
#include <cycloid/tolerance/statistics.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

namespace cycloid
{
  namespace runs
  {
    namespace u = results::units;

    namespace
    {
      using results::Clock;
      using results::seconds_since;

      /** The figures of Study::figures, in order, under their names in
       * stiffness.csv (load_sharing is computed from the first). */
      const char *figure_names[] = {"K_secant_Nm_per_rad",
                                    "K_tangent_Nm_per_rad",
                                    "rotation_rad",
                                    "max_pin_force_N",
                                    "pins_in_contact"};

      /** @p e's message alone (deal.II's what() adds the source line). */
      std::string
      message_of(const dealii::ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        std::string text = info.str();
        while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
          text.pop_back();
        return text;
      }

      /** A CSV file for rank 0, with the precision of the run's others. */
      std::ofstream
      csv_file(const std::string &path)
      {
        std::ofstream out(path);
        AssertThrow(out, dealii::ExcMessage("cannot write " + path));
        out << std::setprecision(12);
        return out;
      }

      /** Write @p s as the statistics columns of a summary row. */
      void
      write_summary(std::ostream &out, const tolerance::Summary &s)
      {
        out << s.nominal << ',' << s.mean << ',' << s.std << ',' << s.p05 << ','
            << s.p50 << ',' << s.p95 << ',' << s.min << ',' << s.max;
      }
    } // namespace



    template <int dim>
    ToleranceRun<dim>::ToleranceRun(const Settings &settings,
                                    const MPI_Comm  comm)
      : settings(settings)
      , comm(comm)
      , angles(settings.loading.crank_angles(
          geometry::CycloidGeometry(settings.model.stage.geometry)
            .mesh_period()))
      , torques(settings.loading.torque_values())
      , n_pins(settings.model.stage.geometry.n_pins)
      , n_discs(settings.model.stage.scene.n_discs)
      , sampler(settings.study,
                tolerance::StageDeviations::from_rows(
                  settings.model.stage.geometry.n_pins,
                  settings.model.stage.geometry.pin_deviations,
                  settings.model.stage.geometry.disc_deviations))
    {
      // The analytical model of the mean stage checks the geometry on every
      // rank (a bad file fails everywhere alike).
      analytic::StageModel model(settings.model.stage.model_settings());
      (void)model;
    }



    template <int dim>
    int
    ToleranceRun<dim>::load_sign() const
    {
      bool positive = false, negative = false;
      for (const double t : torques)
        {
          positive |= t > 0;
          negative |= t < 0;
        }
      return positive && negative ? 0 : (negative ? -1 : 1);
    }



    template <int dim>
    typename ToleranceRun<dim>::SampleSolver
    ToleranceRun<dim>::reduced_solver()
    {
      const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      {
        // The coarse model lives only while it is condensed: the samples
        // need the condensed compliance alone.
        const auto                start = Clock::now();
        reduced::CoarseModel<dim> coarse(settings.model,
                                         angles.front(),
                                         angles.back() - angles.front(),
                                         load_sign(),
                                         comm);
        std::ostream *progress = root && dim == 3 ? &std::cout : nullptr;
        for (const double psi : angles)
          nominal.push_back(std::make_unique<reduced::ReducedModel<dim>>(
            settings.model, coarse, psi, load_sign(), progress));
        if (root)
          std::cout << "  reduced model of sample 0: " << coarse.dofs()
                    << " DoFs, " << nominal.front()->n_contacts()
                    << " contacts condensed at " << angles.size()
                    << " crank angle(s) in " << seconds_since(start)
                    << " s; every sample reuses this compliance" << std::endl;
      }
      return [this](const tolerance::StageDeviations &d) {
        reduced::ReducedSettings s       = settings.model;
        s.stage.geometry.pin_deviations  = d.pins;
        s.stage.geometry.disc_deviations = d.discs;
        s.stage.geometry.check_drawing   = false;
        std::vector<results::StageState> states;
        for (unsigned int k = 0; k < angles.size(); ++k)
          {
            auto                             start = Clock::now();
            const reduced::ReducedModel<dim> model(s, *nominal[k]);
            double                           beta = 0;
            for (unsigned int t = 0; t < torques.size(); ++t)
              {
                const analytic::LoadState load =
                  settings.loading.torque_cycle && torques[t] == 0 ?
                    model.zero_torque_limit(
                      parameters::LoadingParameters::zero_side(torques, t)) :
                    model.solve(torques[t], beta);
                beta                      = load.rotation;
                results::StageState state = model.stage_state(load);
                state.step                = states.size();
                state.wall_s              = seconds_since(start);
                start                     = Clock::now();
                states.push_back(state);
              }
          }
        return states;
      };
    }



    template <int dim>
    typename ToleranceRun<dim>::SampleSolver
    ToleranceRun<dim>::analytic_solver() const
    {
      return [this](const tolerance::StageDeviations &d) {
        analytic::ModelSettings m  = settings.model.stage.model_settings();
        m.geometry.pin_deviations  = d.pins;
        m.geometry.disc_deviations = d.discs;
        m.geometry.check_drawing   = false;
        std::vector<results::StageState> states;
        auto                             start = Clock::now();
        const analytic::StageModel       model(m);
        for (const double psi : angles)
          {
            const auto pins = model.unloaded_pins(psi);
            double     beta = 0;
            for (unsigned int t = 0; t < torques.size(); ++t)
              {
                const analytic::LoadState load =
                  settings.loading.torque_cycle && torques[t] == 0 ?
                    model.zero_torque_limit(
                      pins,
                      parameters::LoadingParameters::zero_side(torques, t)) :
                    model.solve(pins, torques[t], beta);
                beta                      = load.rotation;
                results::StageState state = model.stage_state(load, psi);
                state.step                = states.size();
                state.wall_s              = seconds_since(start);
                start                     = Clock::now();
                states.push_back(state);
              }
          }
        return states;
      };
    }



    template <int dim>
    std::vector<typename ToleranceRun<dim>::OverStates>
    ToleranceRun<dim>::over_states() const
    {
      std::vector<OverStates> list;
      const double            nan = std::numeric_limits<double>::quiet_NaN();
      if (settings.loading.torque_cycle)
        for (const double psi : angles)
          for (const char *name : {"torsional_rigidity_Nm_per_arcmin",
                                   "lost_motion_arcmin",
                                   "backlash_arcmin"})
            list.push_back(
              {name, psi * u::deg_per_rad, settings.loading.rated_torque});
      if (angles.size() > 1)
        for (const double t : torques)
          list.push_back({"transmission_error_pp_arcsec", nan, t});
      return list;
    }



    template <int dim>
    std::vector<double>
    ToleranceRun<dim>::cycle_figures(
      const std::vector<results::StageState> &states) const
    {
      std::vector<double> f;
      const unsigned int  n_t = torques.size();
      if (settings.loading.torque_cycle)
        for (unsigned int k = 0; k < angles.size(); ++k)
          {
            std::vector<postprocess::TorsionPoint> curve;
            for (unsigned int t = 0; t < n_t; ++t)
              {
                const results::StageState &s = states[k * n_t + t];
                curve.push_back({s.crank, torques[t], s.rotation, s.takeup});
              }
            const auto c = postprocess::catalogue_figures(
              curve,
              settings.loading.rated_torque,
              parameters::LoadingParameters::lost_motion_torque);
            f.insert(f.end(),
                     {c.rigidity_Nm_per_arcmin,
                      c.lost_motion_arcmin,
                      c.backlash_arcmin});
          }
      if (angles.size() > 1)
        for (unsigned int t = 0; t < n_t; ++t)
          {
            double lo = 1e300, hi = -1e300;
            for (unsigned int k = 0; k < angles.size(); ++k)
              {
                lo = std::min(lo, states[k * n_t + t].rotation);
                hi = std::max(hi, states[k * n_t + t].rotation);
              }
            f.push_back((hi - lo) * u::arcsec_per_rad);
          }
      return f;
    }



    template <int dim>
    std::vector<double>
    ToleranceRun<dim>::figures_of(
      const std::vector<results::StageState> &states) const
    {
      std::vector<double> f;
      for (const results::StageState &s : states)
        {
          f.insert(f.end(),
                   {s.k_secant(),
                    s.k_tangent,
                    s.rotation,
                    s.max_pin_force(),
                    double(s.pins_in_contact())});
          std::vector<double> fn(n_discs * n_pins, 0.);
          for (const auto &p : s.pins)
            if (p.disc < n_discs && p.pin < n_pins)
              fn[p.disc * n_pins + p.pin] = p.fn;
          f.insert(f.end(), fn.begin(), fn.end());
        }
      if (!states.empty())
        {
          const std::vector<double> over = cycle_figures(states);
          f.insert(f.end(), over.begin(), over.end());
        }
      return f;
    }



    template <int dim>
    typename ToleranceRun<dim>::Study
    ToleranceRun<dim>::solve_study(const SampleSolver        &solve,
                                   const tolerance::BandMask &on,
                                   const std::string         &label,
                                   const bool                 keep_rows)
    {
      const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(comm);
      const unsigned int               n     = settings.study.n_samples + 1;
      const auto                       start = Clock::now();
      std::vector<std::vector<double>> figures;
      std::vector<std::string>         rows, failures;
      const unsigned int mine  = (n - rank + n_ranks - 1) / n_ranks;
      auto               shown = start;
      for (unsigned int s = rank, i = 0; s < n; s += n_ranks, ++i)
        {
          std::vector<results::StageState> states;
          std::string                      failure;
          try
            {
              states = solve(sampler.draw(s, on));
            }
          catch (const dealii::ExceptionBase &e)
            {
              // The mean stage must solve; a sample that cannot (a pin
              // overlapping a disc at rest) is counted and left out.
              if (s == 0)
                throw;
              failure = message_of(e);
            }
          figures.push_back(figures_of(states));
          failures.push_back(failure);
          std::ostringstream text;
          text << std::setprecision(12);
          if (keep_rows)
            for (const results::StageState &state : states)
              {
                text << s << ',';
                postprocess::write_row(
                  text,
                  postprocess::stiffness_columns(),
                  postprocess::StiffnessRow{
                    state, false, std::numeric_limits<double>::quiet_NaN()});
              }
          rows.push_back(text.str());
          // Progress every 5 s (a study of seconds says nothing).
          if (rank == 0 && seconds_since(shown) > 5)
            {
              shown = Clock::now();
              std::cout << "    " << label << ": about " << (i + 1) * n_ranks
                        << " of " << n << " samples (" << std::setprecision(3)
                        << 100. * (i + 1) / mine << " %), "
                        << seconds_since(start) << " s" << std::endl;
            }
        }
      Study study;
      study.wall_s = dealii::Utilities::MPI::max(seconds_since(start), comm);
      const auto all_figures = dealii::Utilities::MPI::gather(comm, figures, 0);
      const auto all_rows    = dealii::Utilities::MPI::gather(comm, rows, 0);
      const auto all_failures =
        dealii::Utilities::MPI::gather(comm, failures, 0);
      if (rank != 0)
        return study;
      for (unsigned int s = 0; s < n; ++s)
        {
          study.figures.push_back(all_figures[s % n_ranks][s / n_ranks]);
          study.rows.push_back(all_rows[s % n_ranks][s / n_ranks]);
          study.failures.push_back(all_failures[s % n_ranks][s / n_ranks]);
        }
      return study;
    }



    template <int dim>
    void
    ToleranceRun<dim>::write_study(const Study &study) const
    {
      const std::string  dir      = settings.model.stage.output_directory;
      const unsigned int n        = study.figures.size();
      const unsigned int n_states = angles.size() * torques.size();
      const unsigned int stride   = n_figures + n_discs * n_pins;
      {
        std::ofstream out = csv_file(dir + "/samples.csv");
        out << "sample,"
            << postprocess::header(postprocess::stiffness_columns()) << '\n';
        for (const std::string &rows : study.rows)
          out << rows;
      }
      const std::vector<double> &nominal = study.figures[0];
      // The figure @p f of state @p k of every solved sample but the mean.
      const auto values = [&](const unsigned int k, const unsigned int f) {
        std::vector<double> v;
        for (unsigned int s = 1; s < n; ++s)
          if (!study.figures[s].empty())
            v.push_back(study.figures[s][k * stride + f]);
        return v;
      };
      std::ofstream out = csv_file(dir + "/tolerance_summary.csv");
      out << "quantity,crank_deg,torque_Nm,nominal,mean,std,p05,p50,p95,min,"
             "max,standard_error\n";
      std::ofstream pins = csv_file(dir + "/pin_force_summary.csv");
      pins << "crank_deg,torque_Nm,disc,pin,nominal,mean,std,p05,p50,p95,min,"
              "max,standard_error\n";
      // A torque cycle passes a torque twice at a crank angle (loading and
      // unloading: the same state without friction): one row each.
      std::set<std::pair<double, double>> written;
      for (unsigned int k = 0; k < n_states; ++k)
        {
          const double crank  = angles[k / torques.size()] * u::deg_per_rad;
          const double torque = torques[k % torques.size()];
          if (!written.insert({crank, torque}).second)
            continue;
          const auto row = [&](const std::string        &name,
                               const tolerance::Summary &s) {
            out << name << ',' << crank << ',' << torque + 0. << ',';
            write_summary(out, s);
            out << ',' << s.standard_error << '\n';
          };
          for (unsigned int f = 0; f < n_figures; ++f)
            row(figure_names[f],
                tolerance::summarise(nominal[k * stride + f], values(k, f)));
          // The seed's lambda, computed: K_secant over the mean stage's.
          std::vector<double> lambda = values(k, 0);
          for (double &x : lambda)
            x /= nominal[k * stride];
          row("load_sharing", tolerance::summarise(1., lambda));
          for (unsigned int p = 0; p < n_discs * n_pins; ++p)
            {
              const auto s =
                tolerance::summarise(nominal[k * stride + n_figures + p],
                                     values(k, n_figures + p));
              if (!(s.max > 0) && !(s.nominal > 0))
                continue;
              pins << crank << ',' << torque + 0. << ',' << p / n_pins << ','
                   << p % n_pins << ',';
              write_summary(pins, s);
              pins << ',' << s.standard_error << '\n';
            }
        }
      // The figures over states (catalogue figures, TE peak-to-peak).
      const std::vector<OverStates> over = over_states();
      std::set<double>              te_written; // the TE per torque, once each
      for (unsigned int i = 0; i < over.size(); ++i)
        {
          if (std::isnan(over[i].crank) &&
              !te_written.insert(over[i].torque).second)
            continue;
          std::vector<double> v;
          for (unsigned int s = 1; s < n; ++s)
            if (!study.figures[s].empty())
              v.push_back(study.figures[s][n_states * stride + i]);
          const auto sum =
            tolerance::summarise(nominal[n_states * stride + i], v);
          out << over[i].name << ',' << over[i].crank << ','
              << over[i].torque + 0. << ',';
          write_summary(out, sum);
          out << ',' << sum.standard_error << '\n';
        }
      // The extreme samples: the lowest and highest stiffness (K_secant
      // over the mean stage's, the worst state of each sample) and peak pin
      // force, as deviation files for any model.
      const std::string extremes = dir + "/extreme-samples";
      std::filesystem::create_directories(extremes);
      struct Extreme
      {
        const char  *name;
        unsigned int figure;
        bool         lowest;
      };
      std::ofstream list = csv_file(extremes + "/extremes.csv");
      list << "name,sample,crank_deg,torque_Nm,quantity,value,nominal\n";
      for (const Extreme &x : {Extreme{"kmin", 0, true},
                               Extreme{"kmax", 0, false},
                               Extreme{"fmin", 3, true},
                               Extreme{"fmax", 3, false}})
        {
          unsigned int best = 0, best_k = 0;
          double       best_ratio = x.lowest ? 1e300 : -1e300;
          for (unsigned int s = 1; s < n; ++s)
            for (unsigned int k = 0; k < n_states && !study.figures[s].empty();
                 ++k)
              {
                const double ref = nominal[k * stride + x.figure];
                if (!(ref > 0))
                  continue;
                const double r = study.figures[s][k * stride + x.figure] / ref;
                if (x.lowest ? r < best_ratio : r > best_ratio)
                  best_ratio = r, best = s, best_k = k;
              }
          if (best == 0)
            continue;
          sampler.draw(best, tolerance::Sampler::all_bands())
            .write(extremes + "/" + x.name + "-pins.csv",
                   extremes + "/" + x.name + "-discs.csv");
          list << x.name << ',' << best << ','
               << angles[best_k / torques.size()] * u::deg_per_rad << ','
               << torques[best_k % torques.size()] << ','
               << figure_names[x.figure] << ','
               << study.figures[best][best_k * stride + x.figure] << ','
               << nominal[best_k * stride + x.figure] << '\n';
        }
    }



    template <int dim>
    void
    ToleranceRun<dim>::write_sensitivity(
      const Study                                       &study,
      const std::vector<std::pair<unsigned int, Study>> &alone) const
    {
      const unsigned int n_states = angles.size() * torques.size();
      const unsigned int stride   = n_figures + n_discs * n_pins;
      // The standard deviation of figure @p f of state @p k in @p s.
      const auto spread =
        [&](const Study &s, const unsigned int k, const unsigned int f) {
          std::vector<double> v;
          for (unsigned int i = 1; i < s.figures.size(); ++i)
            if (!s.figures[i].empty())
              v.push_back(s.figures[i][k * stride + f]);
          return tolerance::summarise(0., v).std;
        };
      std::ofstream out = csv_file(settings.model.stage.output_directory +
                                   "/tolerance_sensitivity.csv");
      out << "quantity,crank_deg,torque_Nm,tolerance,band,std,share,"
             "sum_of_shares_over_total\n";
      for (unsigned int k = 0; k < n_states; ++k)
        for (const unsigned int f : {0u, 2u, 3u})
          {
            const double        total = std::pow(spread(study, k, f), 2);
            double              sum   = 0;
            std::vector<double> var;
            for (const auto &[b, s] : alone)
              {
                var.push_back(std::pow(spread(s, k, f), 2));
                sum += var.back();
              }
            for (unsigned int i = 0; i < alone.size(); ++i)
              out << figure_names[f] << ','
                  << angles[k / torques.size()] * u::deg_per_rad << ','
                  << torques[k % torques.size()] + 0. << ','
                  << tolerance::band_name(alone[i].first) << ','
                  << tolerance::band_width(settings.study, alone[i].first)
                  << ',' << std::sqrt(var[i]) << ','
                  << (sum > 0 ? var[i] / sum : 0.) << ','
                  << (total > 0 ? sum / total : 0.) << '\n';
          }
    }



    template <int dim>
    void
    ToleranceRun<dim>::run()
    {
      const bool  root  = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const auto  start = Clock::now();
      const auto &p     = settings.study;
      if (root)
        {
          std::cout
            << "cycloid-contact: tolerance study, " << p.n_samples
            << " samples ("
            << (p.distribution ==
                    tolerance::ToleranceParameters::Distribution::normal ?
                  "normal, band = +-3 sigma" :
                  "uniform")
            << ", seed " << p.seed << ") with the " << p.model_name()
            << " model, " << stage::description(settings.model.stage) << ", "
            << angles.size() << " crank angle(s) x " << torques.size()
            << " torque(s); bands:";
          for (unsigned int b = 0; b < tolerance::n_bands; ++b)
            std::cout << (b ? ", " : " ") << tolerance::band_name(b) << " "
                      << tolerance::band_width(p, b);
          std::cout << std::endl;
        }
      const SampleSolver solve =
        p.model == tolerance::ToleranceParameters::Model::reduced ?
          reduced_solver() :
          analytic_solver();
      const Study study =
        solve_study(solve, tolerance::Sampler::all_bands(), "samples", true);
      if (root)
        {
          write_study(study);
          unsigned int failed = 0;
          std::string  first;
          for (unsigned int s = 0; s < study.failures.size(); ++s)
            if (!study.failures[s].empty() && failed++ == 0)
              first = "sample " + std::to_string(s) + ": " + study.failures[s];
          const unsigned int ranks =
            dealii::Utilities::MPI::n_mpi_processes(comm);
          std::cout << "  " << study.figures.size() << " samples (the mean "
                    << "stage and " << p.n_samples << " drawn) in "
                    << study.wall_s << " s on " << ranks << " rank(s): "
                    << study.wall_s * ranks / study.figures.size() * 1e3
                    << " ms per sample and rank ("
                    << study.wall_s / study.figures.size() /
                         (angles.size() * torques.size()) * ranks * 1e3
                    << " ms per state)" << std::endl;
          if (failed > 0)
            std::cout << "  WARNING: " << failed
                      << " sample(s) could not be assembled and are left out "
                         "of the statistics; first: "
                      << first << std::endl;
        }
      std::vector<std::pair<unsigned int, Study>> alone;
      unsigned int                                n_on = 0;
      for (unsigned int b = 0; b < tolerance::n_bands; ++b)
        n_on += tolerance::band_width(p, b) > 0;
      if (p.sensitivity && n_on >= 2)
        for (unsigned int b = 0; b < tolerance::n_bands; ++b)
          if (tolerance::band_width(p, b) > 0)
            {
              tolerance::BandMask on{};
              on[b] = true;
              alone.emplace_back(
                b, solve_study(solve, on, tolerance::band_name(b), false));
            }
      if (root)
        {
          if (!alone.empty())
            write_sensitivity(study, alone);
          std::cout << "  results in " << settings.model.stage.output_directory
                    << "/: samples.csv, tolerance_summary.csv, "
                       "pin_force_summary.csv, "
                    << (alone.empty() ? "" : "tolerance_sensitivity.csv, ")
                    << "extreme-samples/; " << seconds_since(start)
                    << " s in all" << std::endl;
        }
    }



    template class ToleranceRun<2>;
    template class ToleranceRun<3>;
  } // namespace runs
} // namespace cycloid
