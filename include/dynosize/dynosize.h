// dynosize as a library: the one header a program built against the installed package includes
// (find_package(dynosize CONFIG) and target dynosize::dynosize; docs/library.md). It brings in the public API by area; each header states its own rules and cites
// docs/model.md. Every module header is installed too (<dynosize/model/drive.h> can also be named
// as "model/drive.h"), for a program that needs one area only.
//
//   catalog     Catalog::Load, CatalogFolders, BundledCatalogDir, ResolveCatalogFolders
//   model       Drive (the Brown & Chopra motor + ESC model, docs/model.md eqs 42-59), OperatingPoint
//   missions    ReadMission, Combination, MissionEvaluator, AddObjectiveRange, SearchCatalog
//   studies     study::ParseVary, RunPoint, RunSweep (a mission over a grid of values), SweepCsv
//   calibration Calibrate (fit catalog entries to stand logs), Diagnose
//   errors      dynosize::Error and its exit codes (UsageError, DataError, NoInputError, ...)
#pragma once

#include "battery/battery.h"
#include "calibration/calibrate.h"
#include "catalog/catalog.h"
#include "catalog/catalog_path.h"
#include "common/error.h"
#include "common/units.h"
#include "diagnosis/diagnose.h"
#include "mission/mission.h"
#include "model/drive.h"
#include "optimization/credibility.h"
#include "optimization/mission_eval.h"
#include "optimization/objective_range.h"
#include "optimization/search.h"
#include "prop/prop_model.h"
#include "report/sweep_report.h"
#include "study/sweep.h"

// The catalog installed with the package this program is built against is its default catalog
// (catalog/catalog_path.h BundledCatalogDir, step 4): dynosizeConfig.cmake passes its location,
// and it is registered once, before main.
#ifdef DYNOSIZE_PACKAGE_CATALOG_DIR
namespace dynosize::package_detail {
inline const bool kCatalogRegistered = (SetPackageCatalogDir(DYNOSIZE_PACKAGE_CATALOG_DIR), true);
}  // namespace dynosize::package_detail
#endif

// The version of the installed package ("0.1.0"), as `dynosize --version` prints it.
#ifndef DYNOSIZE_VERSION
#error "DYNOSIZE_VERSION is set by the target dynosize::dynosize: link it rather than adding the include path alone"
#endif
