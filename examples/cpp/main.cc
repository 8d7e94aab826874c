// dynosize used as a library (docs/library.md): load the bundled catalog,
// run the paper's motor + ESC pair at one operating point, and fly the quadcopter mission with
// one fixed combination, printing a few numbers.
//
//   dynosize_example [MISSION]      (default: examples/missions/quadcopter_1p5kg.json)
//
// Exit codes as the CLI's: a dynosize::Error carries its own (65 bad data, 66 missing file, ...).
#include <dynosize/dynosize.h>

#include <cstdio>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  using namespace dynosize;
  const std::string mission_path = argc > 1 ? argv[1] : EXAMPLE_MISSION;
  try {
    // The bundled catalog (an installed package finds its own), plus $DYNOSIZE_CATALOG_PATH.
    const CatalogFolders folders = ResolveCatalogFolders("", {}, /*override_ids=*/false);
    const Catalog catalog = Catalog::Load(folders);
    std::cout << "catalog " << folders.base << ": " << catalog.motors().size() << " motors, "
              << catalog.escs().size() << " ESCs, " << catalog.props().size() << " props, "
              << catalog.batteries().size() << " batteries\n";

    // The paper's pair on a hysteresis brake: 11.1 V, 80 % throttle, 0.05 N*m.
    const Drive drive(catalog.motor("emax_1900kv_paper").params, catalog.esc("multistar_30a_paper").params);
    const OperatingPoint p = drive.AtTorque(11.1, 0.8, 0.05);
    std::printf("simulate: %.0f rpm, IDC %.2f A, system efficiency %.1f %%\n", p.rpm, p.idc_a,
                100.0 * p.eta_system);

    // The quadcopter mission flown by the README's pick (4S pack of 5 Ah cells).
    const Mission mission = ReadMission(mission_path);
    Combination c;
    c.motor = &catalog.motor("dc_m_365");
    c.esc = &catalog.esc("dc_e_56");
    c.prop = &catalog.prop("dc_p_231");
    c.battery = &catalog.battery("dc_b_363");
    c.cells = 4;
    MissionResult r = MissionEvaluator(mission, c).Solve();
    AddObjectiveRange(mission, c, &r);
    std::printf("evaluate: %s; mission %.2f min, %.2f Wh; thrust/weight %.2f; mass %.3f kg\n",
                r.feasible ? "feasible" : "infeasible", r.endurance_s / 60.0, r.energy_wh,
                r.thrust_to_weight, r.total_mass_kg);
    return 0;
  } catch (const Error& e) {
    std::cerr << "dynosize_example: " << e.what() << "\n";
    return static_cast<int>(e.code());
  }
}
