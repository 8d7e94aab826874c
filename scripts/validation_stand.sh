#!/usr/bin/env bash
# Regenerates docs/validation_stand.md: `dynosize validate-stand` on every stand table in
# ../shared/data whose motor (and, where named, propeller) is in the bundled catalog, dynosize
# beside the plain first-order DC model, with a measured-vs-predicted figure per table in
# docs/img/validation_stand/. Deterministic: the same build, catalog and data give the same file.
#   usage: scripts/validation_stand.sh [path/to/dynosize] [shared/data dir]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$here/build/dynosize}
data=${2:-$here/../shared/data}
out=$here/docs/validation_stand.md
img=$here/docs/img/validation_stand
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v jq >/dev/null || { echo "validation_stand.sh needs jq" >&2; exit 69; }
s=$data/sjkim_mfr_motor_tables
[ -d "$s" ] || { echo "validation_stand.sh: $s: no such folder" >&2; exit 66; }
esc=dc_e_154  # Castle Phoenix 125: 1 mOhm stated, 125 A (the tables' ESCs are not in the catalog)

# Column maps of the tables (sjkim's README lists the columns).
tm=(--format mapped --map throttle=throttle --map vdc_v=voltage_V --map idc_a=current_A --map rpm=rpm
    --map torque_nm=torque_Nm --map "thrust_n=thrust_g [g]")
at2814=(--format mapped --map throttle=Throttle --map vdc_v=Voltage --map idc_a=Current --map rpm=Rpm
        --map "torque_nm=Torque [N*m]" --map "thrust_n=Thrust [g]")
scorpion=(--format mapped --map throttle=throttle --map vdc_v=voltage_V --map idc_a=current_A --map rpm=rpm
          --map torque_nm=torque_Nm)
# A-4220: the ESC pulse width is the command (its "Throttle" column is not: 0.618 at 1236 us).
a4220=(--format mapped --drop-incomplete-rows --map "throttle=ESC throttle (us) [us]" --map vdc_v=Voltage
       --map idc_a=Current --map rpm=RPM --map torque_nm=Torque --map "thrust_n=Thrust [kgf]")

# case SLUG LABEL CATALOG_DIR TABLE MOTOR PROP|- [extra args...]: writes $tmp/SLUG.json
case_run() {
  local slug=$1 label=$2 cat=$3 table=$4 motor=$5 prop=$6; shift 6
  echo "$label" > "$tmp/$slug.label"
  # An entry the catalog no longer holds (merged, excluded by the propeller audit) is reported,
  # not fatal.
  local id
  for id in "$motor" "$prop"; do
    if [ "$id" != - ] && ! "$exe" --catalog "$cat" catalog show "$id" > /dev/null 2>&1; then
      echo "$id" > "$tmp/$slug.missing"
      return
    fi
  done
  local p=(); [ "$prop" != - ] && p=(--prop "$prop")
  local plot=(); [ "$cat" = "$here/catalog" ] && [ -z "$suffix" ] && plot=(--plot "$img/$slug")
  "$exe" validate-stand --catalog "$cat" "$table" --motor "$motor" --esc $esc "${p[@]}" "$@" "${plot[@]}" \
    --json > "$tmp/$slug.json" 2> "$tmp/$slug.err" || { cat "$tmp/$slug.err" >&2; exit 70; }
}
# A stand-in JSON for a case whose entry is missing: every value prints as "-".
missing_json() { [ -f "$tmp/$1.json" ] || echo '{"errors": {}, "rows_used": 0}' > "$tmp/$1.json"; }
# v SLUG MODE MODEL COLUMN: the MAE rounded to 0.1, or "-"
v() {
  jq -r --arg m "$2" --arg o "$3" --arg c "$4" \
    '.errors[$m][$o][$c].mae // null | if . == null then "-" else (. * 10 | round / 10 | tostring) end' "$tmp/$1.json"
}
bias() {  # SLUG COLUMN: dynosize's mean signed error at the measured rpm, rounded to 0.1
  jq -r --arg c "$2" '.errors.at_measured_rpm.dynosize[$c].bias // null |
    if . == null then "-" else (. * 10 | round / 10 | tostring) end' "$tmp/$1.json"
}
pair() { echo "$(v "$1" "$2" dynosize "$3") / $(v "$1" "$2" plain_dc "$3")"; }
better() {  # "yes" when dynosize's MAE is at most the baseline's (+0.05 for rounding)
  jq -r --arg m "$2" --arg c "$3" \
    '(.errors[$m].dynosize[$c].mae) as $a | (.errors[$m].plain_dc[$c].mae) as $b |
     if $a == null or $b == null then "-" elif $a <= $b + 0.05 then "yes" else "**no**" end' "$tmp/$1.json"
}
goal() {  # SLUG COLUMN LIMIT
  jq -r --arg c "$2" --argjson l "$3" \
    '.errors.at_measured_rpm.dynosize[$c].mae // null | if . == null then "-" elif . <= $l then "yes" else "**no**" end' \
    "$tmp/$1.json"
}

rm -rf "$img"
mkdir -p "$img"
cat_main=$here/catalog
prop_cases=(at3520_13x6.5_dc_p_131 at3520_14x7_apc_per3_14x7e at3520_14x7_dc_p_145 at4125_15x8_apc_per3_15x8e at4125_15x8_dc_p_261)
suffix=""
run_props() {  # CATALOG_DIR SUFFIX [extra validate-stand args...]
  suffix=$2
  local extra=("${@:3}")
  case_run "at3520_13x6.5_dc_p_131$2" "AT3520 550KV + APC 13x6.5 | dc_p_131 APC E 13.0x6.5 (DriveCalc law)" "$1" \
    "$s/TMotor_AT3520_550kv.csv" sj_m_tmotor_at3520_550kv dc_p_131 "${tm[@]}" --where "prop=APC 13x6.5" "${extra[@]}"
  case_run "at3520_14x7_apc_per3_14x7e$2" "AT3520 550KV + APC 14x7 | apc_per3_14x7e APC 14x7E (PER3, computed)" "$1" \
    "$s/TMotor_AT3520_550kv.csv" sj_m_tmotor_at3520_550kv apc_per3_14x7e "${tm[@]}" --where "prop=APC 14x7" "${extra[@]}"
  case_run "at3520_14x7_dc_p_145$2" "AT3520 550KV + APC 14x7 | dc_p_145 APC E 14.0x7.0 (DriveCalc law)" "$1" \
    "$s/TMotor_AT3520_550kv.csv" sj_m_tmotor_at3520_550kv dc_p_145 "${tm[@]}" --where "prop=APC 14x7" "${extra[@]}"
  case_run "at4125_15x8_apc_per3_15x8e$2" "AT4125 540KV + APC 15x8 | apc_per3_15x8e APC 15x8E (PER3, computed)" "$1" \
    "$s/TMotor_AT4125_540kv.csv" sj_m_tmotor_at4125_540kv apc_per3_15x8e "${tm[@]}" "${extra[@]}"
  case_run "at4125_15x8_dc_p_261$2" "AT4125 540KV + APC 15x8 | dc_p_261 APC E 15.0x8.0 (DriveCalc law)" "$1" \
    "$s/TMotor_AT4125_540kv.csv" sj_m_tmotor_at4125_540kv dc_p_261 "${tm[@]}" "${extra[@]}"
  suffix=""
}
run_props "$cat_main" ""
motor_cases=(at2814_1200kv scorpion_1100kv a4220_540kv)
case_run at2814_1200kv "T-Motor AT2814 1200KV (4S; no propeller named)" "$cat_main" "$s/TMotor_AT2814_1200kv.csv" \
  sj_m_tmotor_at2814_1200kv - "${at2814[@]}"
case_run scorpion_1100kv "Scorpion 1100KV (6S; no thrust column)" "$cat_main" "$s/Scorpion_1100kv.csv" \
  sj_m_scorpion_1100kv - "${scorpion[@]}"
case_run a4220_540kv "A-4220 540KV + Falcon 15x10E (not in the catalog)" "$cat_main" "$s/A4220_540kv_stand_test.csv" \
  sj_m_a4220_540kv - "${a4220[@]}"

# The resistance convention (issue 13 item 2): the same tables with rm_ohm x 0.7492 for the
# sjkim motors, when the catalog still stores the DC-equivalent resistance there.
rm_now=$(jq '.motors[] | select(.id == "sj_m_tmotor_at4125_540kv") | .rm_ohm' "$cat_main/sjkim_mfr_tables.json")
preview=no
if [ "$rm_now" = "0.081" ]; then
  preview=yes
  cp -r "$cat_main" "$tmp/cat"
  jq '.motors |= map(.rm_ohm *= 0.7492)' "$cat_main/sjkim_mfr_tables.json" > "$tmp/cat/sjkim_mfr_tables.json"
  run_props "$tmp/cat" "_rms"
fi
# The DC model with the DC equivalents of the catalog's numbers ((Rm + RESC)/0.7492, 1.1095*Io):
# one model with the rms model under an ideal ESC, so what is left is the ESC model.
run_props "$cat_main" "_dceq" --baseline dc-equivalent

label() {
  local l; l=$(cut -d'|' -f"$2" "$tmp/$1.label" | sed 's/^ *//; s/ *$//')
  if [ "$2" = 2 ] && [ -f "$tmp/$1.missing" ]; then l="$l: **$(cat "$tmp/$1.missing") not in the catalog**"; fi
  echo "$l"
}
for f in "$tmp"/*.label; do missing_json "$(basename "$f" .label)"; done
rows() { jq .rows_used "$tmp/$1.json"; }
{
echo "# Stand-table validation (generated by scripts/validation_stand.sh - do not edit)"
echo
echo "\`dynosize validate-stand\` on the stand tables in ../shared/data whose motor is in the bundled"
echo "catalog. Every row is predicted through catalog entries only (nothing is fitted to the table), by"
echo "dynosize's rms model (model.md eqs 42-59) and by the plain first-order DC model side by side:"
echo
echo "    KT_dc = 60/(2*pi*Kv),  I = Io + Q/KT_dc,  U = n/Kv + R*I,  ESC a lossless chopper: U = d*VDC, IDC = d*I"
echo
echo "with the catalog's label Kv and the same numbers dynosize gets: R = rm_ohm + resc_ohm, Io = io_a"
echo "(src/stand/dc_baseline.h). ESC: $esc (Castle Phoenix 125, 1 mOhm stated; the tables' ESCs are not in the"
echo "catalog, and the sjkim rm_ohm already includes ESC and wiring). Its C1, C0, tr_sat and sat_slope are the"
echo "catalog prior (ideal C1/C0, knee at 90 % with slope 0.61: assumed). Air density 1.225 kg/m^3."
echo
echo "Each cell is the mean absolute error in percent, **dynosize / plain DC**, over the table's rows:"
echo
echo "- **@rpm**: at the measured rpm. The propeller entry gives thrust and torque at that speed, the"
echo "  model gives the DC current (the issue's goal: thrust <= 8 %, current <= 10 %). Thrust is the"
echo "  propeller's alone, so both models share it."
echo "- **@rpm+Q**: at the measured rpm and the measured torque: the motor + ESC alone, without the"
echo "  propeller's error."
echo "- **fwd**: forward from the table's throttle column (the propeller's torque law sets the speed)."
echo
echo "## Tables with the same propeller product in the catalog"
echo
echo "| table | propeller entry | rows | thrust @rpm | IDC @rpm | IDC @rpm+Q | thrust <= 8 % | IDC <= 10 % | IDC @rpm not worse than DC | IDC @rpm+Q not worse |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  echo "| $(label $c 1) | $(label $c 2) | $(rows $c) | $(pair $c at_measured_rpm thrust_n) | $(pair $c at_measured_rpm idc_a) |"\
" $(pair $c at_measured_rpm_and_torque idc_a) | $(goal $c thrust_n 8) | $(goal $c idc_a 10) |"\
" $(better $c at_measured_rpm idc_a) | $(better $c at_measured_rpm_and_torque idc_a) |"
done
echo
echo "Propeller torque at the measured rpm against the measured torque (the same for both models):"
echo
echo "| table | propeller entry | torque MAE % (bias %) | thrust bias % |"
echo "|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  echo "| $(label $c 1) | $(label $c 2) | $(v $c at_measured_rpm dynosize torque_nm) ($(bias $c torque_nm)) | $(bias $c thrust_n) |"
done
echo
echo "### Forward from the throttle column"
echo
echo "| table | propeller entry | rpm fwd | thrust fwd | IDC fwd | throttle needed at the measured rpm, error in points |"
echo "|---|---|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  echo "| $(label $c 1) | $(label $c 2) | $(pair $c from_throttle rpm) | $(pair $c from_throttle thrust_n) |"\
" $(pair $c from_throttle idc_a) | $(pair $c at_measured_rpm_and_torque throttle) |"
done
echo
echo "## Tables without a catalog propeller: the measured torque as the load"
echo
echo "| table | rows | IDC @rpm+Q | rpm fwd (torque held) | IDC @rpm+Q not worse than DC | throttle needed, error in points |"
echo "|---|---|---|---|---|---|"
for c in "${motor_cases[@]}"; do
  echo "| $(label $c 1) | $(rows $c) | $(pair $c at_measured_rpm idc_a) | $(pair $c from_throttle rpm) |"\
" $(better $c at_measured_rpm idc_a) | $(pair $c at_measured_rpm throttle) |"
done
echo
echo "The A-4220 table's throttle is read from its ESC pulse width (1000-2000 us): its \`Throttle\` column is"
echo "not the command (sjkim's README: it differs from the spreadsheet; 0.618 at 1236 us). Both models"
echo "under-predict the Scorpion's current by about 24 %: at 40 % throttle the table draws 159 W for 64 W at"
echo "the shaft (40 % efficient), losses that its catalog entry (label Kv, fitted R, assumed Io) does not"
echo "hold: a speed-dependent no-load current and part-throttle ESC losses (model.md section 9)."
echo
if [ "$preview" = yes ]; then
  echo "## What the resistance-convention fix should do"
  echo
  echo "The sjkim motors store the DC-equivalent resistance fitted to V = R*I + rpm/Kv as \`rm_ohm\`. The rms"
  echo "circuit (eq 42) needs Rm = R_dc*(K*kp)^2/kp = 0.7492*R_dc: with Io = 0 and an ideal ESC the two models"
  echo "then give the same DC current at any (rpm, torque) (test \`StandDcBaseline.RmsModelEqualsDcModelAtTheConvertedResistance\`)."
  echo "Here dynosize runs on a copy of the catalog with rm_ohm x 0.7492 for the sjkim motors, against the plain"
  echo "DC model with the resistance as stored today (its own convention):"
  echo
  echo "| table | propeller entry | IDC @rpm | IDC @rpm+Q | rpm fwd | thrust fwd | IDC fwd |"
  echo "|---|---|---|---|---|---|---|"
  for c in "${prop_cases[@]}"; do
    r=${c}_rms
    echo "| $(label $c 1) | $(label $c 2) | $(v $r at_measured_rpm dynosize idc_a) / $(v $c at_measured_rpm plain_dc idc_a) |"\
" $(v $r at_measured_rpm_and_torque dynosize idc_a) / $(v $c at_measured_rpm_and_torque plain_dc idc_a) |"\
" $(v $r from_throttle dynosize rpm) / $(v $c from_throttle plain_dc rpm) |"\
" $(v $r from_throttle dynosize thrust_n) / $(v $c from_throttle plain_dc thrust_n) |"\
" $(v $r from_throttle dynosize idc_a) / $(v $c from_throttle plain_dc idc_a) |"
  done
  echo
else
  echo "(The catalog no longer stores the DC-equivalent resistance for the sjkim motors: the convention"
  echo "preview is skipped; the tables above are the converted catalog.)"
  echo
fi
# Means over the propeller tables (for the reading below).
mean() {  # SUFFIX MODE MODEL COLUMN
  local f=(); for c in "${prop_cases[@]}"; do f+=("$tmp/$c$1.json"); done
  jq -s -r --arg m "$2" --arg o "$3" --arg c "$4" \
    '[.[] | .errors[$m][$o][$c].mae // empty] | if length == 0 then "-" else add / length * 10 | round / 10 | tostring end' "${f[@]}"
}
echo "## Reading the tables"
echo
echo "(Written against the catalog of the first run, 2026-11-23: the means below are recomputed, the"
echo "other figures in this prose are not; after catalog changes, check them against the tables.)"
echo
echo "- **Thrust at the measured rpm** is the propeller entry alone. Four of the five same-product entries"
echo "  are within 8 % (mean over the five: $(mean "" at_measured_rpm dynosize thrust_n) %); DriveCalc's APC E 15x8 law"
echo "  (dc_p_261) over-predicts by about 10 %."
echo "- **Current at the measured rpm through the propeller** carries the propeller's torque error: APC's"
echo "  computed PER3 tables give 12-13 % less torque than T-Motor measured, the DriveCalc laws -6 to +19 %."
echo "  Where dynosize is better here (the PER3 rows) it is not to its credit: its copper loss is too high by"
echo "  the resistance convention (next point) and that cancels the propeller's low torque."
echo "- **Motor + ESC alone (@rpm+Q)**: with the catalog as it is, dynosize loses to the plain DC model on"
echo "  every T-Motor table (mean over the rows above $(mean "" at_measured_rpm_and_torque dynosize idc_a) % against $(mean "" at_measured_rpm_and_torque plain_dc idc_a) %), and its bias is"
echo "  positive: it over-predicts the current. The cause is the resistance convention: \`rm_ohm\` of the"
echo "  sjkim motors is the DC-equivalent resistance, which the rms circuit turns into kp*Rm*Irms^2 ="
echo "  1.335 x the DC copper loss. With an ideal ESC, the rms model and the DC model are the same model"
echo "  once Rm = 0.7492 x R_dc and Io_rms = Io_dc/1.1095, so any gap here is a units question, not physics."
if [ "$preview" = yes ]; then
echo "  With rm_ohm x 0.7492 (section above) the gap closes: $(mean _rms at_measured_rpm_and_torque dynosize idc_a) % against $(mean "" at_measured_rpm_and_torque plain_dc idc_a) %. The"
echo "  remaining few tenths come from io_a, which these entries store as an rms current (FAST-UAV ratio,"
echo "  catalog/README.md) while the DC model uses it as a DC current."
fi
echo "- **Forward from the throttle** tests the ESC's throttle map more than the motor: at 40 % command the"
echo "  T-Motor tables turn loaded near or above the no-load speed Kv*0.4*VDC of a linear PWM duty (AT4125:"
echo "  4943 rpm measured, 4834 rpm no-load; AT3520 + 13x6.5: 4834 against 4948), so no model with"
echo "  duty = throttle can match them, and the"
echo "  \"throttle needed\" column (the inverse at the measured rpm and torque) is 4-6 points above the command"
echo "  even for the DC model. dynosize loses more here for the reason above: with the DC resistance as"
echo "  rm_ohm its loaded speed drop R*I is 1.335 x the DC model's."
if [ "$preview" = yes ]; then
echo "  With rm_ohm x 0.7492 its forward rpm error is within 0.5 points of the DC model's (mean"
echo "  $(mean _rms from_throttle dynosize rpm) % against $(mean "" from_throttle plain_dc rpm) %); the rest is io_a and the saturation knee that the catalog ESC prior"
echo "  assumes at 90 % (slope 0.61), which touches only the 100 % rows."
fi
echo "  For the throttle map itself, a measured ESC entry (\`dynosize calibrate\` on a table with throttle)"
echo "  is the cure, not the motor model."
echo "- **The goals** (thrust <= 8 % and DC current <= 10 % at the measured rpm, never worse than the"
echo "  plain DC model): thrust is met for 4 of 5 entries. The current is limited by the propeller entries'"
echo "  torque (12-19 % off for three of five), which neither model can fix; on the motor + ESC alone the"
echo "  convention fix brings dynosize level with the DC model (within 0.4 points), which is as good as it can"
echo "  get with the same numbers: the two models differ only where the ESC is not ideal."
echo
echo "## The DC model with the DC equivalents of the catalog's numbers"
echo
echo "\`--baseline dc-equivalent\`: R = (Rm + RESC)/0.7492, Io = 1.1095*io_a. Under an ideal, unsaturated ESC the"
echo "two models then give the same DC current at any speed and torque (test"
echo "\`StandDcBaseline.DcEquivalentNumbersReproduceTheRmsModel\`), so the columns below differ only by the"
echo "catalog ESC prior's saturation knee. This is the fair comparison once the catalog stores rms values;"
echo "with the DC resistance stored as rm_ohm (today's sjkim entries) both models carry the 1.335 x copper loss."
echo
echo "| table | propeller entry | IDC @rpm | IDC @rpm+Q | rpm fwd | IDC fwd |"
echo "|---|---|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  r=${c}_dceq
  echo "| $(label $c 1) | $(label $c 2) | $(pair $r at_measured_rpm idc_a) | $(pair $r at_measured_rpm_and_torque idc_a) |"\
" $(pair $r from_throttle rpm) | $(pair $r from_throttle idc_a) |"
done
echo
cat <<'EOF'
## Stand tables that cannot be matched

- CTU-MRS (Readytosky 2312, Tarot 4114, T-Motor 3110 with DJI, Tarot, T-Motor, Multistar and
  Quantum propellers) and dronebuildcalc (24 motors with Gemfan, HQProp, Flashhobby, Brotherhobby
  propellers): their motors are in the catalog, but no propeller of the same product is, and the
  tables have no torque column, so the load at a row is unknown.
- MIT KDE2814XF-775 and the Tyto database's nine large motors on a T-Motor 16x5.4: their motors
  are not in the catalog.

## Figures

One per table: `docs/img/validation_stand/<table>/stand_measured_vs_predicted.png` (current and
thrust at the measured rpm, current at the measured rpm and torque, rpm and current from the
throttle; dynosize orange, plain DC blue, 1:1 and +-10 % lines). For example
![AT4125 + APC 15x8E](img/validation_stand/at4125_15x8_apc_per3_15x8e/stand_measured_vs_predicted.png)
EOF
} > "$out"
echo "wrote $out and $img/*/" >&2
