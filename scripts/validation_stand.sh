#!/usr/bin/env bash
# Regenerates docs/validation_stand.md: `dynosize validate-stand` on every stand table in
# ../shared/data whose motor (and, where named, propeller) is in the bundled catalog, dynosize
# beside the plain first-order DC model, with a measured-vs-predicted figure per table in
# docs/img/validation_stand/. Every number in the prose is computed here from the runs' JSON
# (nothing hand-written), so the file stays true when the catalog changes. Deterministic: the
# same build, catalog and data give the same file.
#   usage: scripts/validation_stand.sh [path/to/dynosize] [shared/data dir]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$here/build/dynosize}
data=${2:-$here/../shared/data}
out=$here/docs/validation_stand.md
img=$here/docs/img/validation_stand
cat_main=$here/catalog
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

# MIT KDE2814XF-775 (no header, no voltage column: a 3S pack, nominal 11.1 V assumed).
mit=(--format mapped --map "throttle=#1 [us]" --map "torque_nm=#2 [N*m]" --map "thrust_n=#3 [N]" --map rpm=#4
     --map "idc_a=#5 [A]" --vdc 11.1)
m=$data/mit_multicopter_kde2814

# case_run SLUG SUFFIX LABEL TABLE MOTOR PROP|- [extra args...]: writes $tmp/SLUG$SUFFIX.json.
# Figures only for the runs without a suffix (the catalog ESC prior, the default baseline).
case_run() {
  local slug=$1 suffix=$2 label=$3 table=$4 motor=$5 prop=$6; shift 6
  echo "$label" > "$tmp/$slug.label"
  # An entry the catalog no longer holds (merged, excluded by the propeller audit) is reported,
  # not fatal.
  local id
  for id in "$motor" "$prop"; do
    if [ "$id" != - ] && ! "$exe" --catalog "$cat_main" catalog show "$id" > /dev/null 2>&1; then
      echo "$id" > "$tmp/$slug.missing"
      return
    fi
  done
  local p=(); [ "$prop" != - ] && p=(--prop "$prop")
  local plot=(); [ -z "$suffix" ] && plot=(--plot "$img/$slug")
  "$exe" validate-stand --catalog "$cat_main" "$table" --motor "$motor" --esc $esc "${p[@]}" "$@" "${plot[@]}" \
    --json > "$tmp/$slug$suffix.json" 2> "$tmp/$slug$suffix.err" || { cat "$tmp/$slug$suffix.err" >&2; exit 70; }
}
prop_cases=(at3520_13x6.5_dc_p_131 at3520_14x7_apc_per3_14x7e at3520_14x7_dc_p_145 at4125_15x8_apc_per3_15x8e
            at4125_15x8_dc_p_261)
motor_cases=(at2814_1200kv scorpion_1100kv a4220_540kv kde2814_14in kde2814_10in)
run_all() {  # SUFFIX [extra validate-stand args...]
  local x=$1; shift
  case_run at3520_13x6.5_dc_p_131 "$x" "AT3520 550KV + APC 13x6.5 | dc_p_131 APC E 13.0x6.5 (DriveCalc law)" \
    "$s/TMotor_AT3520_550kv.csv" sj_m_tmotor_at3520_550kv dc_p_131 "${tm[@]}" --where "prop=APC 13x6.5" "$@"
  case_run at3520_14x7_apc_per3_14x7e "$x" "AT3520 550KV + APC 14x7 | apc_per3_14x7e APC 14x7E (PER3, computed)" \
    "$s/TMotor_AT3520_550kv.csv" sj_m_tmotor_at3520_550kv apc_per3_14x7e "${tm[@]}" --where "prop=APC 14x7" "$@"
  case_run at3520_14x7_dc_p_145 "$x" "AT3520 550KV + APC 14x7 | dc_p_145 APC E 14.0x7.0 (DriveCalc law)" \
    "$s/TMotor_AT3520_550kv.csv" sj_m_tmotor_at3520_550kv dc_p_145 "${tm[@]}" --where "prop=APC 14x7" "$@"
  case_run at4125_15x8_apc_per3_15x8e "$x" "AT4125 540KV + APC 15x8 | apc_per3_15x8e APC 15x8E (PER3, computed)" \
    "$s/TMotor_AT4125_540kv.csv" sj_m_tmotor_at4125_540kv apc_per3_15x8e "${tm[@]}" "$@"
  case_run at4125_15x8_dc_p_261 "$x" "AT4125 540KV + APC 15x8 | dc_p_261 APC E 15.0x8.0 (DriveCalc law)" \
    "$s/TMotor_AT4125_540kv.csv" sj_m_tmotor_at4125_540kv dc_p_261 "${tm[@]}" "$@"
  case_run at2814_1200kv "$x" "T-Motor AT2814 1200KV (4S; no propeller named)" "$s/TMotor_AT2814_1200kv.csv" \
    sj_m_tmotor_at2814_1200kv - "${at2814[@]}" "$@"
  case_run scorpion_1100kv "$x" "Scorpion 1100KV (6S; no thrust column)" "$s/Scorpion_1100kv.csv" \
    sj_m_scorpion_1100kv - "${scorpion[@]}" "$@"
  case_run a4220_540kv "$x" "A-4220 540KV + Falcon 15x10E (not in the catalog)" "$s/A4220_540kv_stand_test.csv" \
    sj_m_a4220_540kv - "${a4220[@]}" "$@"
  if [ -d "$m" ]; then
    case_run kde2814_14in "$x" "KDE2814XF-775 + 14x4.8 CF (MIT; VDC 11.1 V assumed)" "$m/motor_14inch_prop.txt" \
      fu_m_105 - "${mit[@]}" "$@"
    case_run kde2814_10in "$x" "KDE2814XF-775 + 10x3.3 CF (MIT; VDC 11.1 V assumed)" "$m/motor_10inch_prop.txt" \
      fu_m_105 - "${mit[@]}" "$@"
  fi
}
rm -rf "$img"
mkdir -p "$img"
run_all ""                               # the catalog ESC prior, the datasheet baseline (defaults)
run_all _ideal --ideal-esc               # the ESC ideal in both models
run_all _stored --baseline as-stored     # the rms numbers fed unchanged to the DC model

# A stand-in JSON for a case whose entry is missing: every value prints as "-".
for f in "$tmp"/*.label; do
  c=$(basename "$f" .label)
  for x in "" _ideal _stored; do [ -f "$tmp/$c$x.json" ] || echo '{"errors": {}, "rows": [], "rows_used": 0}' > "$tmp/$c$x.json"; done
done
r1='def r1: if . == null then "-" else (. * 10 | round / 10 | tostring) end;'
v() {  # FILE MODE MODEL COLUMN: the MAE rounded to 0.1, or "-"
  jq -r --arg m "$2" --arg o "$3" --arg c "$4" "$r1"' .errors[$m][$o][$c].mae // null | r1' "$tmp/$1.json"
}
bias() {  # FILE MODE COLUMN: dynosize's mean signed error, rounded to 0.1
  jq -r --arg m "$2" --arg c "$3" "$r1"' .errors[$m].dynosize[$c].bias // null | r1' "$tmp/$1.json"
}
pair() { echo "$(v "$1" "$2" dynosize "$3") / $(v "$1" "$2" plain_dc "$3")"; }
goal() {  # FILE COLUMN LIMIT
  jq -r --arg c "$2" --argjson l "$3" \
    '.errors.at_measured_rpm.dynosize[$c].mae // null | if . == null then "-" elif . <= $l then "yes" else "**no**" end' \
    "$tmp/$1.json"
}
# Where dynosize's MAE exceeds the DC model's by more than 0.05 (rounding), in every mode and column.
worse() {  # FILE
  jq -r '
    def mn: {"at_measured_rpm": "@rpm", "at_measured_rpm_and_torque": "@rpm+Q", "from_throttle": "fwd"}[.];
    def cn: {"thrust_n": "thrust", "idc_a": "IDC", "rpm": "rpm", "torque_nm": "torque", "throttle": "throttle"}[.];
    . as $r
    | [ $r.errors | to_entries[] | .key as $mode
        | .value.dynosize | to_entries[] | .key as $col
        | ($r.errors[$mode].plain_dc[$col].mae // null) as $b
        | select($b != null and .value.mae > $b + 0.05)
        | "\($mode | mn) \($col | cn) (+\((.value.mae - $b) * 10 | round / 10))" ]
    | if length == 0 then "no" else "yes: " + join(", ") end' "$tmp/$1.json"
}
maxgap() {  # FILE: the largest |dynosize - DC| MAE difference over every mode and column, to 0.1
  jq -r "$r1"' . as $r | [ $r.errors | to_entries[] | .key as $mode | .value.dynosize | to_entries[]
      | .key as $col | ($r.errors[$mode].plain_dc[$col].mae // null) as $b | select($b != null)
      | (.value.mae - $b) | fabs ] | max | r1' "$tmp/$1.json"
}
# The full-throttle rows (measured throttle >= 0.999) forward from the throttle: mean signed rpm
# error of MODEL in percent, to 0.1.
full_rpm() {  # FILE MODEL
  jq -r --arg o "$2" "$r1"' [ .rows[] | select((.measured.throttle // 0) >= 0.999 and .from_throttle[$o] != null)
      | (.from_throttle[$o].rpm / .measured.rpm - 1) * 100 ] | if length == 0 then null else add / length end | r1' \
    "$tmp/$1.json"
}
# At the measured rpm and torque: the DC model's mean signed current error over the rows with
# measured throttle in [LO, HI), to 0.1. MODE is where the measured torque is the load.
cur_bias() {  # FILE MODE LO HI
  jq -r --arg m "$2" --argjson lo "$3" --argjson hi "$4" "$r1"' [ .rows[]
      | select((.measured.throttle // -1) >= $lo and (.measured.throttle // -1) < $hi and .[$m].plain_dc != null)
      | (.[$m].plain_dc.idc_a / .measured.idc_a - 1) * 100 ] | if length == 0 then null else add / length end | r1' \
    "$tmp/$1.json"
}
# Full-throttle rows: the torque per ampere the table implies, Q/(IDC - Io_dc) (at duty 1 the
# DC model's motor current is IDC), against KT_dc = 60/(2*pi*Kv): excess in percent, to 0.1.
kt_excess() {  # FILE
  jq -r "$r1"' .baseline as $b | [ .rows[] | select((.measured.throttle // 0) >= 0.999)
      | (.measured.torque_nm / (.measured.idc_a - $b.io_a)) / $b.kt_nm_per_a * 100 - 100 ]
      | if length == 0 then null else add / length end | r1' "$tmp/$1.json"
}
# Full-throttle rows: measured loss VDC*IDC - Q*omega against the DC model's R*I^2 + Io*U at
# (rpm, Q): "measured W / model W".
loss_pair() {  # FILE
  jq -r '.baseline as $b | [ .rows[] | select((.measured.throttle // 0) >= 0.999)
      | (.measured.torque_nm / $b.kt_nm_per_a + $b.io_a) as $i
      | (.measured.rpm / $b.kv_rpm_per_v + $b.r_ohm * $i) as $u
      | [.vdc_v * .measured.idc_a - .measured.torque_nm * .measured.rpm * 3.141592653589793 / 30,
         $b.r_ohm * $i * $i + $b.io_a * $u] ] | if length == 0 then "-" else
      "\(map(.[0]) | add / length | round) W / \(map(.[1]) | add / length | round) W" end' "$tmp/$1.json"
}
baseline_of() {  # FILE: "R mOhm, Io A"
  jq -r '.baseline | "\(.r_ohm * 1e4 | round / 10) mOhm, Io \(.io_a * 1000 | round / 1000) A"' "$tmp/$1.json"
}
label() {
  [ -f "$tmp/$1.label" ] || { echo "$1 (data not found)"; return; }
  local l; l=$(cut -d'|' -f"$2" "$tmp/$1.label" | sed 's/^ *//; s/ *$//')
  if [ "$2" = 2 ] && [ -f "$tmp/$1.missing" ]; then l="$l: **$(cat "$tmp/$1.missing") not in the catalog**"; fi
  echo "$l"
}
rows() { jq .rows_used "$tmp/$1.json"; }
mean() {  # SUFFIX MODE MODEL COLUMN: the mean MAE over the propeller tables
  local f=(); for c in "${prop_cases[@]}"; do f+=("$tmp/$c$1.json"); done
  jq -s -r --arg m "$2" --arg o "$3" --arg c "$4" "$r1"' [.[] | .errors[$m][$o][$c].mae // empty] |
    if length == 0 then null else add / length end | r1' "${f[@]}"
}
count_goal() {  # COLUMN LIMIT: "k of n"
  local f=(); for c in "${prop_cases[@]}"; do f+=("$tmp/$c.json"); done
  jq -s -r --arg c "$1" --argjson l "$2" '[.[] | .errors.at_measured_rpm.dynosize[$c].mae // empty] |
    "\(map(select(. <= $l)) | length) of \(length)"' "${f[@]}"
}
mfr_note=$(jq -r '.motors[] | select(.id == "sj_m_tmotor_at4125_540kv") | .source.note // ""' "$cat_main/sjkim_mfr_tables.json" |
  grep -o 'rm_dc_ohm fitted from [^)]*)' || true)
esc_line=$(jq -r '.escs[]? | select(.id == "'$esc'") | "\(.name): resc_ohm \(.resc_ohm * 1000) mOhm, c1 \(.c1), c0 \(.c0), tr_sat \(.tr_sat), sat_slope \(.sat_slope)"' "$cat_main"/drivecalc*.json | head -1)

# Figures the prose quotes, from the runs and the catalog.
knee=$(jq -r '.escs[]? | select(.id == "'$esc'") | "\(.tr_sat) + \(.sat_slope)*\(1 - .tr_sat | . * 1000 | round / 1000) = \(.tr_sat + .sat_slope * (1 - .tr_sat) | . * 1000 | round / 10) %"' \
  "$cat_main"/drivecalc*.json | head -1)
resc_mohm=$(jq -r '.escs[]? | select(.id == "'$esc'") | .resc_ohm * 1000' "$cat_main"/drivecalc*.json | head -1)
r_range=$(for c in "${prop_cases[@]}"; do jq -r '.baseline.r_ohm // empty' "$tmp/${c}_ideal.json"; done |
  sort -g | sed -n '1p;$p' | awk '{printf "%s%d", (NR > 1 ? "-" : ""), $1 * 1000 + 0.5}')
idc_gap=$(for c in "${prop_cases[@]}"; do
  for m in at_measured_rpm at_measured_rpm_and_torque; do
    jq -r --arg m "$m" '(.errors[$m].dynosize.idc_a.mae - .errors[$m].plain_dc.idc_a.mae) | fabs' "$tmp/$c.json"
  done; done | sort -g | tail -1 | awk '{printf "%.2f", $1}')
kt_range=$(for c in at3520_13x6.5_dc_p_131 at3520_14x7_apc_per3_14x7e at4125_15x8_apc_per3_15x8e at2814_1200kv; do
  kt_excess ${c}_ideal; done | grep -v -- - | sort -g | sed -n '1p;$p' | paste -sd- -)

{
echo "# Stand-table validation (generated by scripts/validation_stand.sh - do not edit)"
echo
echo "\`dynosize validate-stand\` on the stand tables in ../shared/data whose motor is in the bundled"
echo "catalog. Every row is predicted through catalog entries only (nothing is fitted to the table), by"
echo "dynosize's rms model (model.md eqs 42-59) and by the plain first-order DC model side by side:"
echo
echo "    KT_dc = 60/(2*pi*Kv),  I = Io + Q/KT_dc,  U = n/Kv + R*I,  ESC a lossless chopper: U = d*VDC, IDC = d*I"
echo
echo "The DC model gets what a DC calculator is given for the same parts (\`--baseline datasheet\`, the"
echo "default; src/stand/dc_baseline.h): the label Kv, the datasheet resistance R_dc (the entry's"
echo "\`rm_dc_ohm\`, else rm_ohm/0.7492) plus the ESC's resistance in DC terms (resc_ohm/0.7492) and the"
echo "DC no-load current 1.1095*io_a. The catalog stores the rms circuit's numbers (catalog/conventions.h:"
echo "rm_ohm = 0.7492*R_dc, io_a = Io_dc/1.1095), and with an ideal ESC the rms model and this DC model"
echo "are then one model: at a given speed and torque they give the same DC current (test"
echo "\`StandDcBaseline.DatasheetNumbersReproduceTheRmsModel\`). **Every difference between the two"
echo "columns below is therefore the ESC model**: the catalog ESC's resistance, C1/C0 and its saturation"
echo "knee."
echo
echo "ESC: $esc ($esc_line; the tables' ESCs are not in the catalog). Its C1, C0, tr_sat and sat_slope"
echo "are the catalog prior (assumed). The sjkim motors' R_dc is the table's own full-throttle fit"
echo "(catalog note: \"${mfr_note:-see catalog/README.md}\"), so it already holds the ESC and the wiring. The runs"
echo "with \`--ideal-esc\` (no ESC resistance, no knee) are the fair reading for these tables. Air"
echo "density 1.225 kg/m^3."
echo
echo "Each cell is the mean absolute error in percent, **dynosize / plain DC**, over the table's rows:"
echo
echo "- **@rpm**: at the measured rpm. The propeller entry gives thrust and torque at that speed, and the"
echo "  model gives the DC current. The issue's goal is thrust <= 8 % and current <= 10 %. Thrust is the"
echo "  propeller's alone, so both models share it."
echo "- **@rpm+Q**: at the measured rpm and the measured torque: the motor + ESC alone, without the"
echo "  propeller's error."
echo "- **fwd**: forward from the table's throttle column (the propeller's torque law sets the speed)."
echo
echo "## Tables with the same propeller product in the catalog (catalog ESC prior)"
echo
echo "| table | propeller entry | rows | thrust @rpm | IDC @rpm | IDC @rpm+Q | rpm fwd | thrust <= 8 % | IDC <= 10 % | dynosize worse than DC (MAE points) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  echo "| $(label $c 1) | $(label $c 2) | $(rows $c) | $(pair $c at_measured_rpm thrust_n) | $(pair $c at_measured_rpm idc_a) |"\
" $(pair $c at_measured_rpm_and_torque idc_a) | $(pair $c from_throttle rpm) | $(goal $c thrust_n 8) | $(goal $c idc_a 10) |"\
" $(worse $c) |"
done
echo
echo "Goals at the measured rpm: thrust <= 8 % on $(count_goal thrust_n 8) entries (mean $(mean "" at_measured_rpm dynosize thrust_n) %);"
echo "DC current <= 10 % on $(count_goal idc_a 10) (mean $(mean "" at_measured_rpm dynosize idc_a) %; DC model $(mean "" at_measured_rpm plain_dc idc_a) %)."
echo
echo "### The same with an ideal ESC (\`--ideal-esc\`)"
echo
echo "| table | propeller entry | IDC @rpm | IDC @rpm+Q | rpm fwd | thrust fwd | IDC fwd | throttle needed @rpm+Q, points | dynosize worse than DC |"
echo "|---|---|---|---|---|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  i=${c}_ideal
  echo "| $(label $c 1) | $(label $c 2) | $(pair $i at_measured_rpm idc_a) | $(pair $i at_measured_rpm_and_torque idc_a) |"\
" $(pair $i from_throttle rpm) | $(pair $i from_throttle thrust_n) | $(pair $i from_throttle idc_a) |"\
" $(pair $i at_measured_rpm_and_torque throttle) | $(worse $i) |"
done
echo
echo "### Why dynosize is worse where it is"
echo
echo "At @rpm and @rpm+Q both models see the same speed and torque. The ESC's knee does not enter there:"
echo "the DC current follows from the voltage the motor needs, eq (57) with the effective throttle. Only"
echo "the ESC's resistance separates them ($resc_mohm mOhm against R_dc of $r_range mOhm) and the two IDC columns"
echo "agree within $idc_gap points. The throttle needed at those points does see the knee: above tr_sat"
echo "the prior asks for more command for the same voltage, hence the \"throttle\" entries in the last"
echo "column. Forward from the throttle the prior's knee delivers $knee"
echo "of the voltage at a 100 % command. Mean rpm error on the 100 % rows,"
echo "forward, dynosize / DC model (catalog prior):"
echo
echo "| table | propeller entry | 100 % rows: rpm error fwd % | same, --ideal-esc | largest gap dynosize - DC with --ideal-esc (points) |"
echo "|---|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  echo "| $(label $c 1) | $(label $c 2) | $(full_rpm $c dynosize) / $(full_rpm $c plain_dc) |"\
" $(full_rpm ${c}_ideal dynosize) / $(full_rpm ${c}_ideal plain_dc) | $(maxgap ${c}_ideal) |"
done
echo
echo "With the propeller's torque law as the load, the knee can look like a gain: the PER3 and DriveCalc"
echo "entries give too little torque at high rpm, so both models spin too fast at 100 %, and the knee"
echo "pulls dynosize back. That is one error cancelling another. With the measured torque as the load"
n_fwd_worse=0; for c in "${motor_cases[@]}"; do case $(worse $c) in *"fwd rpm"*) n_fwd_worse=$((n_fwd_worse + 1));; esac; done
echo "(tables without a catalog propeller, below) it makes dynosize's forward rpm worse on $n_fwd_worse of ${#motor_cases[@]} tables."
echo "The sjkim R_dc comes from a fit to these"
echo "same full-throttle rows, so it already holds whatever the table's ESC lost at 100 %. Applying the"
echo "prior's knee on top counts that drop twice, and so does adding a catalog ESC's resistance. When the"
echo "table's ESC is unknown and the motor was fitted with it in the loop, the prior should not apply:"
echo "\`--ideal-esc\` is the honest setting. The two models are then identical: the largest gap above is"
echo "rounding (rm_ohm is stored to 3 digits). dynosize's ESC model can only beat the DC model with a"
echo "*measured* ESC entry (\`dynosize calibrate\` on a table with throttle)."
echo
echo "## Why both models miss the current on the T-Motor tables"
echo
echo "Both models share the same error at @rpm+Q, so it does not come from the ESC model. The DC model's"
echo "signed current error at the measured rpm and torque (\`--ideal-esc\`), by throttle band:"
echo
echo "| table | DC model R, Io | 40-60 % rows | 80-100 % rows | torque per ampere at 100 % vs 60/(2*pi*Kv) | loss at 100 %: measured / DC model |"
echo "|---|---|---|---|---|---|"
for c in at3520_13x6.5_dc_p_131 at3520_14x7_apc_per3_14x7e at4125_15x8_apc_per3_15x8e at2814_1200kv; do
  i=${c}_ideal
  m=at_measured_rpm_and_torque; case " ${motor_cases[*]} " in *" $c "*) m=at_measured_rpm;; esac
  echo "| $(label $c 1) | $(baseline_of $i) | $(cur_bias $i $m 0.35 0.6) % | $(cur_bias $i $m 0.8 1.01) % |"\
" +$(kt_excess $i) % | $(loss_pair $i) |"
done
echo
echo "- **At high load both over-predict.** At 100 % the tables give more torque per ampere than the label"
echo "  Kv allows. At duty 1 the motor current is at most IDC, so Q <= KT_dc*(IDC - Io). Yet the"
echo "  measured torque exceeds that bound by the percentage in the table. The measured loss"
echo "  VDC*IDC - Q*omega is also well below what R_dc*I^2 + Io*U needs at the same point. R_dc was fitted"
echo "  to the full-throttle speed drop, V - rpm/Kv = R*I. That drop includes the ESC, the wiring and any"
echo "  commutation or inductive drop that costs speed but no power. So R_dc over-states the copper loss,"
echo "  and label Kv under-states the torque per ampere (the T-Motor torque columns imply a KT $kt_range % above"
echo "  60/(2*pi*Kv); the importer found the same: Io from the torque columns comes out negative). A"
echo "  model fed R_dc and label Kv must over-predict the current where the torque is large. This is"
echo "  the data's inconsistency with the first-order DC circuit, not a units question. The fix is a"
echo "  motor entry calibrated on a dyno log (\`dynosize calibrate\`), not the model."
echo "- **At part throttle the error shrinks or turns negative.** There the table draws more than a"
echo "  lossless chopper and a constant Io allow: ESC switching losses (C0 > 0, model.md eq 62) and a no-load current that grows"
echo "  with speed (section 9). The catalog prior assumes an ideal C1/C0 and a constant, assumed Io"
echo "  (0.0215 x the table's largest current)."
echo "- **The ESC resistance is counted twice with the catalog prior.** The sjkim R_dc holds the ESC and"
echo "  the wiring, and $esc adds $resc_mohm mOhm (divided by 0.7492 in DC terms). The effect on the current is small:"
echo "  IDC @rpm+Q mean $(mean "" at_measured_rpm_and_torque dynosize idc_a) % with the prior against"
echo "  $(mean _ideal at_measured_rpm_and_torque dynosize idc_a) % with \`--ideal-esc\` (dynosize, propeller tables)."
echo
echo "Propeller torque at the measured rpm against the measured torque (the same for both models). It"
echo "sets the current error at @rpm on top of the above:"
echo
echo "| table | propeller entry | torque MAE % (bias %) | thrust bias % |"
echo "|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  echo "| $(label $c 1) | $(label $c 2) | $(v $c at_measured_rpm dynosize torque_nm) ($(bias $c at_measured_rpm torque_nm)) | $(bias $c at_measured_rpm thrust_n) |"
done
echo
echo "## Tables without a catalog propeller: the measured torque as the load"
echo
echo "| table | rows | IDC @rpm+Q | rpm fwd (torque held) | throttle needed, points | dynosize worse than DC (catalog prior) | with --ideal-esc |"
echo "|---|---|---|---|---|---|---|"
for c in "${motor_cases[@]}"; do
  echo "| $(label $c 1) | $(rows $c) | $(pair $c at_measured_rpm idc_a) | $(pair $c from_throttle rpm) |"\
" $(pair $c at_measured_rpm throttle) | $(worse $c) | $(worse ${c}_ideal) |"
done
echo
echo "The A-4220 table's throttle is read from its ESC pulse width (1000-2000 us). Its \`Throttle\` column"
echo "is not the command: sjkim's README says it differs from the spreadsheet (0.618 at 1236 us)."
echo "Both models miss the Scorpion's current by the same amount (DC model bias"
echo "$(bias scorpion_1100kv_ideal at_measured_rpm idc_a) % at the measured rpm and torque). Its table loses more than its"
echo "catalog entry holds (label Kv, fitted R, assumed Io): a speed-dependent no-load current and"
echo "part-throttle ESC losses (model.md section 9)."
echo
eff_max() {  # FILE: the largest shaft power / (VDC*IDC) over the rows, percent
  jq -r '[.rows[] | .measured.torque_nm * .measured.rpm * 3.141592653589793 / 30 / (.vdc_v * .measured.idc_a) * 100]
    | if length == 0 then "-" else max | round | tostring end' "$tmp/$1.json"
}
if [ -f "$tmp/kde2814_10in.label" ]; then
echo "The MIT tables (KDE2814XF-775, catalog entry fu_m_105 from KDE's datasheet via FAST-UAV; Castle"
echo "QuadPack 35, not in the catalog) have no voltage column: VDC is the 3S pack's nominal 11.1 V, an"
echo "assumption. Both the current at the measured rpm and torque and the forward speed scale with it."
echo "With 11.1 V the 10-inch sweep's shaft power reaches $(eff_max kde2814_10in) % of VDC*IDC (14-inch:"
echo "$(eff_max kde2814_14in) %), more than a motor of this size and its ESC deliver: that pack was probably nearer"
echo "its full 12.6 V. The two sweeps of the same motor and ESC therefore cannot both be read at one"
echo "voltage, so the gap between them says little about the model. dynosize runs fu_m_105 with the"
echo "in-system law of KDE's datasheets (R x2.18, Io x3.28: docs/in-system-law.md, fitted and checked on"
echo "KDE's own sheets, which state their voltage), the DC model with the datasheet values: at an assumed"
echo "voltage under which the shaft power already reaches $(eff_max kde2814_10in) % of VDC*IDC, every loss"
echo "the law adds shows as error, so these tables cannot check the law (the KDE sheets do)."
echo "The forward rpm error is large in relative terms because of the slow rows: a few points of throttle"
echo "(the ESC's pulse-width map) are a large share of 800-1500 rpm."
echo
fi
echo "## The DC model fed the catalog's rms numbers (\`--baseline as-stored\`)"
echo
echo "The DC model with R = rm_ohm + resc_ohm and Io = io_a: 0.7492 x the datasheet R and 0.90 x its"
echo "Io. A DC calculator is never given these numbers. The table shows what mixing the conventions"
echo "does; it is not a baseline:"
echo
echo "| table | propeller entry | IDC @rpm | IDC @rpm+Q | rpm fwd |"
echo "|---|---|---|---|---|"
for c in "${prop_cases[@]}"; do
  r=${c}_stored
  echo "| $(label $c 1) | $(label $c 2) | $(pair $r at_measured_rpm idc_a) | $(pair $r at_measured_rpm_and_torque idc_a) |"\
" $(pair $r from_throttle rpm) |"
done
echo
echo "With the smaller R and Io, the DC model's current at @rpm+Q comes out lower. Because R_dc"
echo "over-states the loss at high load (above), that happens to land closer to these tables"
echo "(mean $(mean _stored at_measured_rpm_and_torque plain_dc idc_a) % against $(mean "" at_measured_rpm_and_torque plain_dc idc_a) % with the datasheet numbers). It is right for the wrong reason."
echo
cat <<'EOF'
## Stand tables that cannot be matched

- **CTU-MRS** (Readytosky 2312, Tarot 4114, T-Motor 3110, with DJI 9450, Aliexpress/CF 9450,
  plastic 8045, T-Motor 1147, Multistar 1045, Quantum 1150, Tarot 1155/1555/1575 propellers) and
  **dronebuildcalc** (24 motors with Gemfan, HQProp, Flashhobby, Brotherhobby propellers): their
  motors are in the catalog, but no propeller of the same product is. The catalog's nearest ones
  (APC 10x4.5MR, EPP1045, DJI CF 15x5.0) are other products, and the tables have no torque
  column, so the load at a row is unknown.
- **MIT KDE2814XF-775** propellers (10x3.3 and 14x4.8 carbon, maker not stated): not in the catalog,
  so the MIT tables run above with their measured torque as the load (motor fu_m_105), not through a
  propeller entry.
- **Tyto database, T-Motor 16x5.4** (KDE 4014XF, NeuMotor 3819, T-Motor Antigravity 5008, MN501-S,
  MN4014, U5, U7 x3): none of the nine motors is in the catalog, and neither is the T-Motor 16x5.4
  propeller (the catalog's APC 16x5.5MR is another product). The tables give label Kv in the file
  names (except NeuMotor), voltage, current, rpm and torque, but no resistance. An R_dc could be
  fitted from their full-throttle rows the way the sjkim importer does.
- **elodin 2300 KV + 6x3** (4S): the motor is unnamed (label 2300 KV only) and the propeller's maker
  is unknown. The catalog's 6x3 propellers (APC 6x3R-RH, GWS HD 6x3) cannot be called the same
  product.

## Figures

One per table, `docs/img/validation_stand/<table>/stand_measured_vs_predicted.png` (catalog ESC
prior, datasheet baseline). Each shows the current and thrust at the measured rpm, the current at
the measured rpm and torque, and the rpm and current from the throttle. dynosize is orange, the
plain DC model blue, with 1:1 and +-10 % lines. For example
![AT4125 + APC 15x8E](img/validation_stand/at4125_15x8_apc_per3_15x8e/stand_measured_vs_predicted.png)
EOF
} > "$out"
echo "wrote $out and $img/*/" >&2
