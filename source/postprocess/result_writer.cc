#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cycloid/postprocess/result_writer.h>

#include <filesystem>
#include <iomanip>

namespace cycloid
{
  namespace postprocess
  {
    std::string
    ResultWriter::stiffness_header()
    {
      return "step,crank_deg,torque_Nm,rotation_rad,K_secant_Nm_per_rad,"
             "K_tangent_Nm_per_rad,pins_in_contact,active_set_iterations,dofs,"
             "wall_s,K_secant_Nm_per_arcmin,K_tangent_Nm_per_arcmin,"
             "takeup_rad,K_secant_elastic_Nm_per_rad,reaction_torque_Nm,"
             "max_pin_force_N,linear_iterations,peak_memory_MB";
    }



    std::string
    ResultWriter::pin_forces_header()
    {
      return "step,crank_deg,disc,pin,Fx_N,Fy_N,Fn_N,arm_mm,clearance_um,"
             "phase_deg,approach_um,pair_stiffness_N_per_mm,contact_x_mm,"
             "contact_y_mm,contact_halfwidth_um,hertz_halfwidth_um";
    }



    ResultWriter::ResultWriter(const std::string &directory, const bool active)
      : active(active)
    {
      if (!active)
        return;
      std::error_code ec;
      std::filesystem::create_directories(directory, ec);
      AssertThrow(!ec,
                  dealii::ExcMessage("Output directory '" + directory +
                                     "' cannot be created: " + ec.message()));
      const std::string d = directory + "/";
      stiffness.open(d + "stiffness.csv");
      pin_forces.open(d + "pin_forces.csv");
      AssertThrow(stiffness && pin_forces,
                  dealii::ExcMessage("cannot write to Output directory '" +
                                     directory + "'."));
      stiffness << std::setprecision(12) << stiffness_header() << std::endl;
      pin_forces << std::setprecision(12) << pin_forces_header() << std::endl;
    }



    double
    peak_memory_MB(const MPI_Comm comm)
    {
      dealii::Utilities::System::MemoryStats stats;
      dealii::Utilities::System::get_memory_stats(stats);
      return dealii::Utilities::MPI::sum(static_cast<double>(stats.VmHWM),
                                         comm) /
             1024.;
    }



    void
    write_stiffness_row(std::ostream &out, const StiffnessRow &s)
    {
      out << s.step << ',' << s.crank_deg << ',' << s.torque_Nm << ','
          << s.rotation_rad << ',' << s.k_secant << ',' << s.k_tangent << ','
          << s.pins_in_contact << ',' << s.iterations << ',' << s.dofs << ','
          << s.wall_s << ',' << s.k_secant * rad_per_arcmin << ','
          << s.k_tangent * rad_per_arcmin << ',' << s.takeup_rad << ','
          << s.k_secant_elastic << ',' << s.reaction_torque_Nm << ','
          << s.max_pin_force_N << ',' << s.linear_iterations << ','
          << s.peak_memory_MB << '\n';
    }



    void
    write_pin_force_row(std::ostream &out, const PinForceRow &p)
    {
      out << p.step << ',' << p.crank_deg << ',' << p.disc << ',' << p.pin
          << ',' << p.fx_N << ',' << p.fy_N << ',' << p.fn_N << ',' << p.arm_mm
          << ',' << p.clearance_um << ',' << p.phase_deg << ',' << p.approach_um
          << ',' << p.pair_stiffness_N_per_mm << ',' << p.contact_x_mm << ','
          << p.contact_y_mm << ',' << p.contact_halfwidth_um << ','
          << p.hertz_halfwidth_um << '\n';
    }



    void
    ResultWriter::write(const StiffnessRow             &s,
                        const std::vector<PinForceRow> &pins)
    {
      if (!active)
        return;
      write_stiffness_row(stiffness, s);
      for (const PinForceRow &p : pins)
        write_pin_force_row(pin_forces, p);
      stiffness.flush();
      pin_forces.flush();
    }
  } // namespace postprocess
} // namespace cycloid
