# Parts nobody tuned for (tests/python/MultiAxisSlicerSurvey.py): slices N random parts of each
# of twenty-one families at the defaults, with their G-code, and prints a line per part and a
# summary.
# Run by freecadcmd with the workbench installed (tools/setup.sh install):
#   MAS_SURVEY="12 39 16" freecadcmd tools/survey.py   # 12 parts a family, seed 39, fill_holes 16
# MAS_SURVEY_JSON=FILE also writes the reports as JSON.
import json
import os
import sys

sys.path.insert(0, os.path.join(os.getcwd(), "tests", "python"))

import MultiAxisSlicerSurvey as survey  # noqa: E402


def main():
    per_family, seed, fill_holes = 8, 39, 16.0
    args = os.environ.get("MAS_SURVEY", "").split()
    if args:
        per_family = int(args[0])
    if len(args) > 1:
        seed = int(args[1])
    if len(args) > 2:
        fill_holes = float(args[2])
    print("\nsurvey: %d parts of each family, seed %d, fill_holes %g mm" % (per_family, seed,
                                                                          fill_holes))
    print("%-16s %3s %5s %6s %7s %6s %9s %9s %5s %6s %6s  %s" % (
        "family", "#", "comps", "layers", "seconds", "step", "worst mm2", "total mm2", "over",
        "coll", "travel", "part"))
    reports = []
    for r in survey.survey(per_family, seed, fill_holes):
        reports.append(r)
        what = ", ".join("%s %s" % (k, ("%.3g" % v) if isinstance(v, float) else v)
                         for k, v in r.items() if k not in (
                             "family", "index", "seed", "components", "layers", "seconds", "step",
                             "worst_unsupported", "total_unsupported", "unsupported_layers",
                             "colliding_layers", "travel_collisions", "layers_out_of_bounds",
                             "notes", "filled_holes"))
        print("\n%-16s %3d %5d %6d %7.2f %6.3f %9.2f %9.1f %5d %6d %6d  %s" % (
            r["family"], r["index"], r["components"], r["layers"], r["seconds"], r["step"],
            r["worst_unsupported"], r["total_unsupported"], len(r["unsupported_layers"]),
            r["colliding_layers"], r["travel_collisions"], what), end="")
    print("\n\nsurvey: %d parts in %.1f s; %d with layers in the nozzle's way, %d with travel "
          "meeting something, %d with layers out of the thickness bounds; unsupported area %.1f "
          "mm2 in all (worst %.2f), %d parts over the deflection's tolerance" % (
              len(reports), sum(r["seconds"] for r in reports),
              sum(1 for r in reports if r["colliding_layers"]),
              sum(1 for r in reports if r["travel_collisions"]),
              sum(1 for r in reports if r["layers_out_of_bounds"]),
              sum(r["total_unsupported"] for r in reports),
              max(r["worst_unsupported"] for r in reports),
              sum(1 for r in reports if r["unsupported_layers"])))
    if os.environ.get("MAS_SURVEY_JSON"):
        with open(os.environ["MAS_SURVEY_JSON"], "w") as f:
            json.dump(reports, f, indent=1)


try:
    main()
except Exception as e:  # freecadcmd exits 0 on an uncaught exception: say it and fail loudly
    import traceback
    traceback.print_exc()
    print("survey: FAILED: %s" % e)
    sys.exit(1)
