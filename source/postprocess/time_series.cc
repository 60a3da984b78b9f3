#include <deal.II/base/hdf5.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/full_matrix.h>

#include <cycloid/postprocess/time_series.h>

#include <cstdint>
#include <filesystem>
#include <istream>
#include <ostream>
#include <utility>

namespace cycloid
{
  namespace postprocess
  {
    TimeSeries::TimeSeries(const Attributes &attributes)
      : attributes(attributes)
    {}



    std::vector<std::vector<double> *>
    TimeSeries::all()
    {
      return {&time,
              &crank_deg,
              &torque,
              &rotation,
              &k_secant,
              &kinetic,
              &elastic,
              &external_work,
              &dissipated,
              &balance,
              &penetration,
              &iterations,
              &angular_momentum,
              &fx,
              &fy,
              &fn};
    }



    void
    TimeSeries::add(const results::StageState &s, const results::EnergyState &e)
    {
      time.push_back(e.time_s);
      crank_deg.push_back(s.crank * results::units::deg_per_rad);
      torque.push_back(s.torque);
      rotation.push_back(s.rotation);
      k_secant.push_back(s.k_secant());
      kinetic.push_back(e.kinetic);
      elastic.push_back(e.elastic);
      external_work.push_back(e.external);
      dissipated.push_back(e.dissipated);
      balance.push_back(e.balance);
      penetration.push_back(e.max_penetration_um);
      iterations.push_back(s.iterations);
      angular_momentum.push_back(e.angular_momentum);
      for (const auto &p : s.pins)
        {
          fx.push_back(p.fx);
          fy.push_back(p.fy);
          fn.push_back(p.fn);
        }
    }



    void
    TimeSeries::checkpoint(dynamics::CheckpointArchive &ar)
    {
      for (std::vector<double> *v : all())
        ar.array(*v);
    }



    void
    TimeSeries::write_hdf5(const std::string &dir, const MPI_Comm comm) const
    {
      if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      const unsigned int n   = time.size();
      const unsigned int np  = attributes.n_discs * attributes.n_pins;
      const std::string  tmp = dir + "/transient.h5.tmp";
      {
        dealii::HDF5::File file(tmp,
                                dealii::HDF5::File::FileAccessMode::create);
        file.set_attribute("scheme", attributes.scheme);
        file.set_attribute("time_step_s", attributes.time_step_s);
        file.set_attribute("crank_speed_deg_per_s",
                           attributes.crank_speed_deg_per_s);
        file.set_attribute("number_of_pins", attributes.n_pins);
        file.set_attribute("number_of_discs", attributes.n_discs);
        file.set_attribute(
          "pin_force_layout",
          std::string("pin_forces/*[step, disc * number_of_pins + pin] [N]"));
        const std::vector<std::pair<std::string, const std::vector<double> *>>
          series{{"time_s", &time},
                 {"crank_deg", &crank_deg},
                 {"torque_Nm", &torque},
                 {"rotation_rad", &rotation},
                 {"K_secant_Nm_per_rad", &k_secant},
                 {"kinetic_J", &kinetic},
                 {"elastic_J", &elastic},
                 {"external_work_J", &external_work},
                 {"dissipated_J", &dissipated},
                 {"balance_error_J", &balance},
                 {"max_penetration_um", &penetration},
                 {"active_set_iterations", &iterations},
                 {"angular_momentum_Nms", &angular_momentum}};
        for (const auto &[name, data] : series)
          if (n > 0)
            file.create_dataset<double>(name, {n}).write(*data);
        auto group = file.create_group("pin_forces");
        for (const auto &[name, data] :
             std::vector<std::pair<std::string, const std::vector<double> *>>{
               {"Fx_N", &fx}, {"Fy_N", &fy}, {"Fn_N", &fn}})
          if (n > 0)
            {
              dealii::FullMatrix<double> m(n, np);
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int k = 0; k < np; ++k)
                  m(i, k) = (*data)[i * np + k];
              group.create_dataset<double>(name, {n, np}).write(m);
            }
      }
      std::filesystem::rename(tmp, dir + "/transient.h5");
    }
  } // namespace postprocess
} // namespace cycloid
