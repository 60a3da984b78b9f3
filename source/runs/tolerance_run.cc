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
      return parameters::LoadingParameters::load_sign(torques);
    }



    template <int dim>
    void
    ToleranceRun<dim>::add_torques(
      results::Clock::time_point                                start,
      const std::function<analytic::LoadState(double, double)> &solve,
      const std::function<analytic::LoadState(int)>            &limit,
      const std::function<results::StageState(const analytic::LoadState &)>
                                       &state_of,
      std::vector<results::StageState> &states) const
    {
      double beta = 0;
      for (unsigned int t = 0; t < torques.size(); ++t)
        {
          const analytic::LoadState load =
            settings.loading.torque_cycle && torques[t] == 0 ?
              limit(parameters::LoadingParameters::zero_side(torques, t)) :
              solve(torques[t], beta);
          beta                      = load.rotation;
          results::StageState state = state_of(load);
          state.step                = states.size();
          state.wall_s              = seconds_since(start);
          start                     = Clock::now();
          states.push_back(state);
        }
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
            const auto                       start = Clock::now();
            const reduced::ReducedModel<dim> model(s, *nominal[k]);
            add_torques(
              start,
              [&](const double torque, const double beta) {
                return model.solve(torque, beta);
              },
              [&](const int side) { return model.zero_torque_limit(side); },
              [&](const analytic::LoadState &load) {
                return model.stage_state(load);
              },
              states);
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
        const auto                       start = Clock::now();
        const analytic::StageModel       model(m);
        for (const double psi : angles)
          {
            const auto pins = model.unloaded_pins(psi);
            add_torques(
              states.empty() ? start : Clock::now(),
              [&](const double torque, const double beta) {
                return model.solve(pins, torque, beta, psi);
              },
              [&](const int side) {
                return model.zero_torque_limit(pins, side, psi);
              },
              [&](const analytic::LoadState &load) {
                return model.stage_state(load, psi);
              },
              states);
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
    std::vector<double>
    ToleranceRun<dim>::drawn(const Study &study, const unsigned int i)
    {
      std::vector<double> v;
      for (unsigned int s = 1; s < study.figures.size(); ++s)
        if (!study.figures[s].empty())
          v.push_back(study.figures[s][i]);
      return v;
    }



    template <int dim>
    void
    ToleranceRun<dim>::write_study(const Study &study) const
    {
      const std::string dir = settings.model.stage.output_directory;
      std::ofstream     out = csv_file(dir + "/samples.csv");
      out << "sample," << postprocess::header(postprocess::stiffness_columns())
          << '\n';
      for (const std::string &rows : study.rows)
        out << rows;
      write_summaries(study);
      write_extremes(study);
    }



    template <int dim>
    void
    ToleranceRun<dim>::write_summaries(const Study &study) const
    {
      const std::string          dir = settings.model.stage.output_directory;
      const unsigned int         n_states = angles.size() * torques.size();
      const unsigned int         stride   = n_figures + n_discs * n_pins;
      const std::vector<double> &nominal  = study.figures[0];
      std::ofstream              out = csv_file(dir + "/tolerance_summary.csv");
      out << "quantity,crank_deg,torque_Nm,nominal,mean,std,p05,p50,p95,min,"
             "max,standard_error\n";
      std::ofstream pins = csv_file(dir + "/pin_force_summary.csv");
      pins << "crank_deg,torque_Nm,disc,pin,nominal,mean,std,p05,p50,p95,min,"
              "max,standard_error\n";
      const auto row = [](std::ostream &o, const tolerance::Summary &s) {
        write_summary(o, s);
        o << ',' << s.standard_error << '\n';
      };
      // A torque cycle passes a torque twice at a crank angle (loading and
      // unloading: the same state without friction): one row each.
      std::set<std::pair<double, double>> written;
      for (unsigned int k = 0; k < n_states; ++k)
        {
          const double crank  = angles[k / torques.size()] * u::deg_per_rad;
          const double torque = torques[k % torques.size()] + 0.;
          if (!written.insert({crank, torque}).second)
            continue;
          for (unsigned int f = 0; f < n_figures; ++f)
            {
              out << figure_names[f] << ',' << crank << ',' << torque << ',';
              row(out,
                  tolerance::summarise(nominal[k * stride + f],
                                       drawn(study, k * stride + f)));
            }
          // The seed's lambda, computed: K_secant over the mean stage's.
          std::vector<double> lambda = drawn(study, k * stride);
          for (double &x : lambda)
            x /= nominal[k * stride];
          out << "load_sharing," << crank << ',' << torque << ',';
          row(out, tolerance::summarise(1., lambda));
          for (unsigned int p = 0; p < n_discs * n_pins; ++p)
            {
              const unsigned int i = k * stride + n_figures + p;
              const auto s = tolerance::summarise(nominal[i], drawn(study, i));
              if (s.max > 0 || s.nominal > 0)
                {
                  pins << crank << ',' << torque << ',' << p / n_pins << ','
                       << p % n_pins << ',';
                  row(pins, s);
                }
            }
        }
      // The figures over states (catalogue figures, TE peak-to-peak).
      const std::vector<OverStates> over = over_states();
      std::set<double>              te_written; // the TE per torque, once each
      for (unsigned int i = 0; i < over.size(); ++i)
        if (!std::isnan(over[i].crank) ||
            te_written.insert(over[i].torque).second)
          {
            const unsigned int at = n_states * stride + i;
            out << over[i].name << ',' << over[i].crank << ','
                << over[i].torque + 0. << ',';
            row(out, tolerance::summarise(nominal[at], drawn(study, at)));
          }
    }



    template <int dim>
    void
    ToleranceRun<dim>::write_extremes(const Study &study) const
    {
      // The lowest and highest stiffness (K_secant over the mean stage's,
      // the worst state of each sample) and peak pin force, as deviation
      // files for any model.
      const std::string extremes =
        settings.model.stage.output_directory + "/extreme-samples";
      std::filesystem::create_directories(extremes);
      const unsigned int         n_states = angles.size() * torques.size();
      const unsigned int         stride   = n_figures + n_discs * n_pins;
      const std::vector<double> &nominal  = study.figures[0];
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
          for (unsigned int s = 1; s < study.figures.size(); ++s)
            for (unsigned int k = 0; k < n_states && !study.figures[s].empty();
                 ++k)
              {
                const double ref = nominal[k * stride + x.figure];
                const double r = study.figures[s][k * stride + x.figure] / ref;
                if (ref > 0 && (x.lowest ? r < best_ratio : r > best_ratio))
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
          return tolerance::summarise(0., drawn(s, k * stride + f)).std;
        };
      std::ofstream out = csv_file(settings.model.stage.output_directory +
                                   "/tolerance_sensitivity.csv");
      out << "quantity,crank_deg,torque_Nm,tolerance,band,std,share,"
             "sum_of_shares_over_total\n";
      std::set<std::pair<double, double>> written; // a cycle's repeats
      for (unsigned int k = 0; k < n_states; ++k)
        for (const unsigned int f : {0u, 2u, 3u})
          {
            if (f == 0 && !written
                             .insert({angles[k / torques.size()],
                                      torques[k % torques.size()]})
                             .second)
              break;
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
    ToleranceRun<dim>::announce() const
    {
      const auto &p = settings.study;
      std::cout << "cycloid-contact: tolerance study, " << p.n_samples
                << " samples ("
                << (p.distribution ==
                        tolerance::ToleranceParameters::Distribution::normal ?
                      "normal, band = +-3 sigma" :
                      "uniform")
                << ", seed " << p.seed << ") with the " << p.model_name()
                << " model, " << stage::description(settings.model.stage)
                << ", " << angles.size() << " crank angle(s) x "
                << torques.size() << " torque(s); bands:";
      for (unsigned int b = 0; b < tolerance::n_bands; ++b)
        std::cout << (b ? ", " : " ") << tolerance::band_name(b) << " "
                  << tolerance::band_width(p, b);
      std::cout << std::endl;
      // The defaults draw nothing: say so rather than solve copies.
      if (!p.any())
        std::cout << "  WARNING: every band of Tolerance study is 0 (the "
                     "default), so every sample is the mean stage; set Pin "
                     "position tolerance, Pin radius tolerance, Eccentricity "
                     "tolerance, Disc angle tolerance or Profile tolerance"
                  << std::endl;
    }



    template <int dim>
    void
    ToleranceRun<dim>::print_outcome(const Study &study) const
    {
      unsigned int failed = 0;
      std::string  first;
      for (unsigned int s = 0; s < study.failures.size(); ++s)
        if (!study.failures[s].empty() && failed++ == 0)
          first = "sample " + std::to_string(s) + ": " + study.failures[s];
      const unsigned int ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
      const unsigned int n     = study.figures.size();
      std::cout << "  " << n << " samples (the mean stage and "
                << settings.study.n_samples << " drawn) in " << study.wall_s
                << " s on " << ranks
                << " rank(s): " << study.wall_s * ranks / n * 1e3
                << " ms per sample and rank ("
                << study.wall_s * ranks / n / (angles.size() * torques.size()) *
                     1e3
                << " ms per state)" << std::endl;
      // The headline per state: lambda and the peak pin force.
      const unsigned int stride = n_figures + n_discs * n_pins;
      for (unsigned int k = 0; k < angles.size() * torques.size(); ++k)
        if (torques[k % torques.size()] != 0 && n > 1)
          {
            std::vector<double> lambda = drawn(study, k * stride);
            for (double &x : lambda)
              x /= study.figures[0][k * stride];
            const auto l = tolerance::summarise(1., lambda);
            const auto f =
              tolerance::summarise(study.figures[0][k * stride + 3],
                                   drawn(study, k * stride + 3));
            std::cout << "    crank "
                      << angles[k / torques.size()] * u::deg_per_rad
                      << " deg, T " << torques[k % torques.size()]
                      << " N m: load sharing (K_secant / nominal) P5 " << l.p05
                      << ", P50 " << l.p50 << ", P95 " << l.p95
                      << "; peak pin force nominal " << f.nominal << " N, P95 "
                      << f.p95 << " N" << std::endl;
          }
      if (failed > 0)
        std::cout << "  WARNING: " << failed
                  << " sample(s) could not be assembled and are left out of "
                     "the statistics; first: "
                  << first << std::endl;
    }



    template <int dim>
    void
    ToleranceRun<dim>::run()
    {
      const bool  root  = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const auto  start = Clock::now();
      const auto &p     = settings.study;
      if (root)
        announce();
      const SampleSolver solve =
        p.model == tolerance::ToleranceParameters::Model::reduced ?
          reduced_solver() :
          analytic_solver();
      const Study study =
        solve_study(solve, tolerance::Sampler::all_bands(), "samples", true);
      if (root)
        {
          write_study(study);
          print_outcome(study);
        }
      // The sensitivity: the study once per band with that band alone.
      std::vector<std::pair<unsigned int, Study>> alone;
      unsigned int                                n_on = 0;
      for (unsigned int b = 0; b < tolerance::n_bands; ++b)
        n_on += tolerance::band_width(p, b) > 0;
      for (unsigned int b = 0; b < tolerance::n_bands; ++b)
        if (p.sensitivity && n_on >= 2 && tolerance::band_width(p, b) > 0)
          {
            tolerance::BandMask on{};
            on[b] = true;
            alone.emplace_back(
              b, solve_study(solve, on, tolerance::band_name(b), false));
          }
      if (root && !alone.empty())
        write_sensitivity(study, alone);
      if (root)
        std::cout << "  results in " << settings.model.stage.output_directory
                  << "/: samples.csv, tolerance_summary.csv, "
                     "pin_force_summary.csv, "
                  << (alone.empty() ? "" : "tolerance_sensitivity.csv, ")
                  << "extreme-samples/; " << seconds_since(start) << " s in all"
                  << std::endl;
    }



    template class ToleranceRun<2>;
    template class ToleranceRun<3>;
  } // namespace runs
} // namespace cycloid
