// Importers: the public data sets of ../shared/data turned into catalog JSON with provenance.
//
// One function per data set reads its folder and returns the entries plus a report of what was
// kept and what was dropped and why; ImportAll runs them all and writes catalog/<dataset>.json.
// Importers are pure functions of their input files: no time stamps, stable order (the order
// of the source rows), numbers rounded to stated significant digits, so re-running on the same
// inputs reproduces the committed files byte for byte.
//
// Ids are lowercase and prefixed by data set: dc_ (DriveCalc), fu_ (FAST-UAV), uiuc_,
// apc_ (APC PER3), sj_ (sjkim manufacturer tables), dbc_ (dronebuildcalc), ctu_ (CTU-MRS).
#pragma once

#include <string>

#include "importers/import_common.h"

namespace dynosize {

struct ImportedDataset {
  DatasetReport report;
  std::string comment;  // the document's "comment": origin, licence, cleaning
  Json motors = Json::array();
  Json escs = Json::array();
  Json props = Json::array();
  Json batteries = Json::array();
};

// Excludes by default (key "exclude", note appended, counted in the report's notes) every motor
// whose motor constant is above the envelope of the other windings of its frame
// (catalog/motor_credibility.h).
void ExcludeImplausibleMotors(ImportedDataset* out);

// Audits a propeller entry that is not measured (AuditProp of import_common.h) and keeps it
// in out->props (counting a derating) or drops it with the reason (FM > 1 in its valid range).
void KeepAuditedProp(Json entry, const std::string& example, ImportedDataset* out);

// shared/data/drivecalc: Motors.csv, ESC.csv, Batteries.csv, Props.csv.
ImportedDataset ImportDriveCalc(const std::string& dir);

// The gear ratio a DriveCalc motor name states (docs/model.md section 12): "<N>:1" after the start,
// a space, '/', '-' or '(' ("Kontronik KIRA 650-13/6.7:1", "Feigao 28-8L 4,4:1",
// "Multiplex Permax BL-480/6G (4,4:1)", "Hacker B50 19S-6,7:1"; decimal comma or point), or
// "<N>/1" after a space at the end of the name with a decimal ("Mega ACn 22/10/3 4,4/1").
// ratio 1 and stated false when the name states none (a ':' in other text, "960Kv: T-28", is
// not a ratio); error non-empty for a ratio-like token that is not one the model takes
// ("<N>:<M>" with M != 1, or N below 1 or above 100).
struct NameGearRatio {
  bool stated = false;
  double ratio = 1.0;
  std::string token;  // the text it was read from
  std::string error;
};
NameGearRatio GearRatioFromMotorName(const std::string& name);

// The Kv a motor name states [rpm/V] (the motor's own, as sold): an explicit "kv" token with
// its number attached or one space away on either side ("880kv", "(~6850Kv)", "280 kV",
// "Scorpion HK-4015/1070KV", "KV980", "KV 880", "R2Hobbies KV2736"), 2-5 digits, a whole
// number not preceded by a decimal separator; when a number stands on both sides the attached
// one is the Kv ("EMP-C5065/09 KV270" 270, "HXT 42-60/06 500Kv 15-deg timing" 500), two
// detached numbers or two different Kv in one name state none. Without a "kv" token, two
// makers' naming conventions, checked on DriveCalc's own entries (every direct-drive one of
// them stores that Kv within 5 %): Himax "<frame>-<Kv>" ("Himax HC3516-0840", "Himax
// 2825-2700") and Medusa "MR-<dia>-<len>-<Kv>" ("Medusa MR-028-032-4200").
// stated false when the name states none.
struct NameKv {
  bool stated = false;
  double kv_rpm_per_v = 0.0;
  std::string token;  // the text it was read from
};
NameKv KvFromMotorName(const std::string& name);
// shared/data/fastuav_catalogues: Motors_Data.csv, ESC_data.csv,
// Non-Dominated-Augmented-Batteries.csv, APC_propellers_MR.csv.
ImportedDataset ImportFastUav(const std::string& dir);
// shared/data/uiuc_propdb: volume{1,2,3}_exp.csv.
ImportedDataset ImportUiuc(const std::string& dir);
// shared/data/apc_per3_subset: PER3_*.csv.
ImportedDataset ImportApcPer3(const std::string& dir);
// shared/data/{sjkim_mfr_motor_tables, dronebuildcalc_mfr_tables, ctu_mrs_motor_tests}.
ImportedDataset ImportSjkimTables(const std::string& dir);
ImportedDataset ImportDroneBuildCalc(const std::string& dir);
ImportedDataset ImportCtuMrs(const std::string& dir);

// shared/data/large_props_apc: PER3_*.csv of APC's 24-28 in propellers, as ImportApcPer3.
ImportedDataset ImportApcPer3Large(const std::string& dir);
// shared/data/evtol_motors: the eVTOL survey's motors, constants not stated estimated by
// catalog/motor_estimate.h (fitted on the references of ../heavy_lift_motors and this folder).
ImportedDataset ImportEvtolMotors(const std::string& dir);
// shared/data/heavy_lift_motors: KDE Direct's datasheet tables (kde_datasheets.csv) and the
// corpus's T-Motor and KDE G3 rows (heavy_lift_motors.csv).
ImportedDataset ImportHeavyLiftMotors(const std::string& dir);
// shared/data/kde_direct_mfr_sheets: KDE's propellers (static CT, CP from the measured sweeps)
// and KDE's stand ESC (KDE-UAS125UVC).
ImportedDataset ImportKdeSheetsCatalog(const std::string& dir);
// shared/data/hv_controllers: motor controllers and ESCs for 12S to 800 V (not the FAST-UAV
// rows, which fastuav.json holds).
ImportedDataset ImportHvControllers(const std::string& dir);
// shared/data/packs_and_cells: Tattu 12S/14S packs and Li-ion cells.
ImportedDataset ImportPacksAndCells(const std::string& dir);

// UIUC volume 3 (Aeronaut CAM folders, family "ancf"): the flat CSV lost a decimal point of
// some sizes ("ancf 125.0x6.0" = 12.5 x 6.0 in has P = 0.6, "ancf 13.0x65.0" = 13 x 6.5 in has
// D = 1.3). Decodes diameter and pitch [in] from the blade name into *d_in, *p_in; returns true
// when they differ from the columns passed in. Other families: false, unchanged.
bool DecodeUiucFolderSize(const std::string& blade_name, double* d_in, double* p_in);

// Runs every importer on shared_data_dir/<dataset>/ and writes out_catalog_dir/<dataset>.json
// (atomically, deterministic bytes). Ids must be unique across all data sets and the files
// already in out_catalog_dir (InternalError otherwise: an importer bug). A missing data-set
// folder throws NoInputError; a malformed source file DataError naming file and line.
ImportReport ImportAll(const std::string& shared_data_dir, const std::string& out_catalog_dir);

}  // namespace dynosize
