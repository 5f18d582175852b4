# rubber-crack: a crack seeded from the left edge of a strip pre-stretched to (λx, λy), Marder's rubber lattice
# (physics/rubber-lattice.md §6, rubber-lattice-validation.md §D), in two parts.
# The paper's failure law (results/rubber-crack/table.{csv,md}, snapshot.png): each lever the issue names is a
# separate switch of data/scenes/stretch.ini on a 200 × 40 strip for 1 ms; every run records how far the tip
# went, its speed over the last stretch of advance (λx × reference tip x, fitted), the lattice's own c_T and
# c_L along x at the run's law, the energy balance and the bonds past u_c.
# Energy-neutral failure (law.failure = freeze) with a crack path (crack.path_cutoff_ratio), on 400 × 80 strips
# (results/rubber-crack/freeze.{csv,md}, crack.png, crack-toughened.png): the steady crack, its speed against
# the stretch and b, the strip's height, the path's contrast, toughening and damping, the wedge's angle
# against the Mach angles, and the wake. docs/rubber-run.md discusses the outcome.
#   make -f Makefile.analysis rubber-crack [RC_NODES=300x60] [RC_TMAX=2e-3] [RCF_LENGTH=400] [JOBS=2]
# MINI=1 (the end-to-end test): 60 × 16 and 160 × 20 strips, a few runs of each part.
RC := $(RESULTS)/rubber-crack
RC_NODES ?= $(if $(MINI),60x16,200x40)
RC_TMAX ?= $(if $(MINI),1e-4,1e-3)
RC_SCENE := data/scenes/stretch.ini
RC_COMMON = --stop.t_max $(RC_TMAX) --stop.tip_margin 0.02 --output.frame_interval 1e-4 -q

# The levers, one switch at a time (SI; Δ = 1 mm, β = 0.3 m√a/Δ = 1.04e-2 kg/s).
# The softening law (its u_c set by each run: 2.786e-3 for the levers, from the far field for the stretches).
RC_SOFT_LAW := --law.pair marder-soft --law.cutoff smoothstep --law.cutoff_width 1e-4 --physics.irreversible on \
               --breaking.extra_widths 0.2 --integrator.safety 0.2
RC_SOFT := $(RC_SOFT_LAW) --law.cutoff_length 2.786e-3
RC_OPT_paper :=
RC_OPT_irreversible := --physics.irreversible on
RC_OPT_damped := --physics.irreversible on --physics.damping on
RC_OPT_near-failure := --physics.irreversible on --physics.damping on --damping.kind near_failure --damping.beta 3.46e-2
RC_OPT_toughened := --physics.irreversible on --physics.toughening on
RC_OPT_c1 := --physics.irreversible on --law.pair marder-c1
RC_OPT_kick := --physics.irreversible on --crack.tip_kick 20
RC_OPT_soft := $(RC_SOFT)
RC_OPT_soft-all := $(RC_SOFT) --physics.damping on --damping.kind near_failure --damping.onset 2.69e-3 \
                   --physics.toughening on
# The three-body weight over all bonds (law.three_body_weight = all_bonds): a node that loses a neighbour fades
# to the pair law; alone, with u_c 10 widths above the far field (the far field then stiffer), with the
# softening law, and stretching the sheet with the seed in place (λy from 2 to 3.5 over 1e-3 s).
RC_OPT_weight := --law.three_body_weight all_bonds
RC_OPT_weight-uc10 := --law.three_body_weight all_bonds --law.cutoff_length 3.166e-3 --damping.onset 2e-3
RC_OPT_weight-soft := $(RC_SOFT) --law.three_body_weight all_bonds
RC_OPT_weight-ramp := --law.three_body_weight all_bonds --loading.stretch_y 3.5 --loading.ramp_from_y 2 \
                      --loading.ramp_time 1e-3 --law.cutoff_length 3.874e-3 --toughening.cutoff 5e-3
# The pair law alone (material.b = 0: Mooney-Rivlin with b = 0, so c_T = c_L) with the far field 0.134Δ below
# u_c (about 5 %), irreversible: a rupture runs. The same with a small three-body term, b = 0.02 to 0.25: its
# cut-off 0.008Δ wide (u_c 17 widths above the far field, which then stays Mooney-Rivlin), a bond marked broken
# only 20 widths past u_c (where h ≈ 2e-9: cutting it earlier, mid-cut-off, makes the energy jump by 2-4 %),
# and a smaller step.
RC_PAIR_LAW := --physics.irreversible on --material.b 0 --breaking.extra_widths 0.2 --integrator.safety 0.2
RC_OPT_pair-only := $(RC_PAIR_LAW) --law.cutoff_length 2.8e-3
RC_THREE_BODY := --physics.irreversible on --law.cutoff_length 2.8e-3 --law.cutoff_width 8e-6 \
                 --breaking.extra_widths 20 --integrator.safety 0.1
RC_OPT_three-body-0.02 := $(RC_THREE_BODY) --material.b 0.02
RC_OPT_three-body-0.05 := $(RC_THREE_BODY) --material.b 0.05
RC_OPT_three-body-0.1 := $(RC_THREE_BODY) --material.b 0.1
RC_OPT_three-body-0.25 := $(RC_THREE_BODY) --material.b 0.25
# The paper's failure law at b = 1.5 with the crack path of the freeze runs below (bulk cut-off 1.3 u_c).
RC_OPT_path := $(RC_THREE_BODY) --crack.path_cutoff_ratio 1.3
# Left out of the default list for time (each can still be made by name, e.g. RC_LEVERS=soft-all): the
# softening law with damping and toughening, the weight's variants and three-body-0.05, which repeat the
# outcome of their neighbours in the table.
RC_LEVERS ?= $(if $(MINI),paper weight,paper irreversible damped near-failure toughened c1 kick soft weight pair-only \
             three-body-0.02 three-body-0.1 three-body-0.25 path)
# The stretch across the crack, with the softening law placed 0.02Δ + L above each far field; the pair law
# alone across stretches, u_c 0.134Δ above each far field (none by default: RC_STRETCHES='2.5 3 3.5',
# RC_PAIR_STRETCHES='2 2.5 3.5').
RC_STRETCHES ?= $(if $(MINI),3,)
RC_PAIR_STRETCHES ?=

RC_RUNS := $(foreach l,$(RC_LEVERS),$(RC)/lever-$(l).h5) $(foreach s,$(RC_STRETCHES),$(RC)/stretch-$(s).h5) \
           $(foreach s,$(RC_PAIR_STRETCHES),$(RC)/pair-stretch-$(s).h5)

.PHONY: rubber-crack
rubber-crack: $(RC)/table.md $(RC)/snapshot.png $(RC)/freeze.md $(RC)/crack.png $(RC)/crack-toughened.png
	@cat $(RC)/table.md $(RC)/freeze.md

$(RC)/strip.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen triangular --nodes $(RC_NODES) --spacing 1e-3 -q -o $@

$(RC)/lever-%.h5: $(RC)/strip.h5 $(RC_SCENE) | build
	@echo "rubber-run lever $*"
	$(LAUNCH) $(BIN)/rubber-run $(THREADS_OPT) --scene $(RC_SCENE) $< $(RC_COMMON) $(RC_OPT_$*) -o $@ 2> $(@:.h5=.log)

# rc_stretch_run,STRETCH_Y,OFFSET,LAW: a run at λy = STRETCH_Y with u_c OFFSET spacings above the far-field
# length of the 60° bonds, √(0.36 + 0.75 λy²) Δ at λx = 1.2 (Δ = 1 mm), and the law options LAW.
rc_stretch_run = uc=$$(awk -v l=$(1) -v o=$(2) 'BEGIN { printf "%.6g", 1e-3 * (sqrt(0.36 + 0.75 * l * l) + o) }'); \
	$(LAUNCH) $(BIN)/rubber-run $(THREADS_OPT) --scene $(RC_SCENE) $< $(RC_COMMON) $(3) --loading.stretch_y $(1) \
	  --law.cutoff_length $$uc -o $@ 2> $(@:.h5=.log)

$(RC)/stretch-%.h5: $(RC)/strip.h5 $(RC_SCENE) | build
	@echo "rubber-run stretch_y $*"
	$(call rc_stretch_run,$*,0.12,$(RC_SOFT_LAW))

$(RC)/pair-stretch-%.h5: $(RC)/strip.h5 $(RC_SCENE) | build
	@echo "rubber-run pair law, stretch_y $*"
	$(call rc_stretch_run,$*,0.134,$(RC_PAIR_LAW))

# One row per run: advance of the tip, speed over the last part of the advance (at least 20Δ of it, after the
# first 20Δ), the lattice's wave speeds, the energy change and the bonds past u_c.
rc_attr = h5dump -a /parameters/rubber-run/$(2) $(1) | sed -n 's/.*(0): *"\(.*\)"/\1/p'
$(RC)/row-%.csv: $(RC)/%.h5
	@lx=$$($(call rc_attr,$<,loading.stretch_x)); ly=$$($(call rc_attr,$<,loading.stretch_y)); \
	 ct=$$($(call rc_attr,$<,derived.lattice.c_T_x)); cl=$$($(call rc_attr,$<,derived.lattice.c_L_x)); \
	 uc=$$($(call rc_attr,$<,law.cutoff_length)); d=$$($(call rc_attr,$<,derived.spacing)); \
	 $(BIN)/observables $< --columns crack_tip_reference_x,total_energy,bonds_past_cutoff | grep -v "^#" | tail -n +2 | \
	 awk -F, -v name=$* -v lx=$$lx -v ly=$$ly -v ct=$$ct -v cl=$$cl -v uc=$$uc -v d=$$d ' \
	   NR == 1 { x0 = $$2; e0 = $$3 } { t[NR] = $$1; x[NR] = $$2; e = $$3; b = $$4; n = NR } \
	   END { adv = (x[n] - x0) / d; v = ""; \
	         if (adv >= 40) { sx = st = sxx = stt = stx = 0; k = 0; \
	           for (i = 1; i <= n; i++) if ((x[i] - x0) / d >= 20) { k++; st += t[i]; sx += lx * x[i]; stt += t[i] * t[i]; stx += t[i] * lx * x[i] } \
	           if (k > 2) v = (k * stx - st * sx) / (k * stt - st * st) } \
	         printf "%s,%g,%.4g,%.4g,%.1f,%s,%.4g,%.4g,%s,%s,%.3g,%d\n", name, ly, sqrt(0.36 + 0.75 * ly * ly), uc / d, adv, \
	           v == "" ? "" : sprintf("%.4g", v), ct, cl, v == "" ? "" : sprintf("%.3g", v / ct), \
	           v == "" ? "" : sprintf("%.3g", v / cl), 100 * (e - e0) / e0, b }' > $@

$(RC)/table.csv: $(patsubst $(RC)/%.h5,$(RC)/row-%.csv,$(RC_RUNS))
	@{ echo "run,stretch_y,u0_over_spacing,uc_over_spacing,advance_spacings,speed_m_s,lattice_c_T_m_s,lattice_c_L_m_s,v_over_c_T,v_over_c_L,energy_change_percent,bonds_past_uc"; \
	   cat $^; } > $@

$(RC)/table.md: $(RC)/table.csv
	@{ echo "# rubber-crack: seeded crack in a pre-stretched strip ($(RC_NODES) nodes, λx = 1.2, t_max = $(RC_TMAX) s)"; echo; \
	   echo "A steady crack needs at least 40Δ of advance here (speed fitted after the first 20Δ); empty speed: it did not run."; echo; \
	   echo "| run | λy | u0/Δ | u_c/Δ | advance (Δ) | v (m/s) | c_T lattice | c_L lattice | v/c_T | v/c_L | ΔE/E (%) | bonds past u_c |"; \
	   echo "|---|---|---|---|---|---|---|---|---|---|---|---|"; \
	   tail -n +2 $< | awk -F, '{ printf "| %s |", $$1; for (i = 2; i <= NF; i++) printf " %s |", $$i; printf "\n" }'; } > $@

# The run whose tip went furthest, at its last frame, bonds coloured by strain relative to the cut-off.
$(RC)/snapshot.png: $(RC)/table.csv
	@best=$$(tail -n +2 $< | sort -t, -k5 -g | tail -1 | cut -d, -f1); \
	 echo "snapshot of $$best"; \
	 $(LAUNCH) $(BIN)/render $(RC)/$$best.h5 --frame -1 --axes -q -o $@

# ---- Energy-neutral failure (law.failure = freeze) with a crack path (crack.path_cutoff_ratio) ----
# No cut-off function (law.cutoff = none: h ≡ 1, the far field is exactly Mooney-Rivlin at any u_c); a bond
# fails for good at u_c, freezing the three-body terms that contain it. The step is set by hand: the
# automatic one (1.8e-6 s) lets the energy drift by 18 % through a crack; 2.5e-7 s keeps it within 0.4 % at
# λy = 3, 2 % at most here (1.25e-7 s gives the same speed). Runs are named by their settings:
#   f-b<b>-y<λy>-c<λc>-p<ratio>[-tough][-damp][-h<rows>]
# b = material.b, λy the stretch across the crack (λx = 1.2), u_c = u_0(λc) + 0.134Δ where u_0(λc) is the
# longest far-field bond at λy = λc (λc = λy: u_c follows the far field, the strain ahead of the tip fixed;
# λc = 4: one u_c, 3.65Δ, for every stretch: one material, stretched more or less), the bulk's cut-off ratio ×
# u_c (the bonds across the crack line keep u_c: a weak plane), toughening of retracting faces (cut-off 5Δ),
# near-failure Kelvin damping (β = 0.3 m√a/Δ from u_c − 0.1Δ), and the strip's height in rows (RCF_ROWS).
RCF_LENGTH ?= $(if $(MINI),160,400)
RCF_ROWS ?= $(if $(MINI),20,80)
RCF_TMAX ?= $(if $(MINI),8e-4,2.5e-3)
RCF_COMMON := --law.failure freeze --law.cutoff none --integrator.dt 2.5e-7 --stop.t_max $(RCF_TMAX) \
              --stop.tip_margin 0.02 --output.frame_interval 2.5e-4 -q
RCF_tough := --physics.toughening on --toughening.cutoff 5e-3
RCF_damp = --physics.damping on --damping.kind near_failure --damping.onset $$(awk -v u=$$uc 'BEGIN { print u - 1e-4 }')
# The steady crack; its speed against the stretch with u_c following the far field, and with one u_c for all
# stretches, for three values of b; the strip's height; the path's contrast, toughening and damping.
RCF_STEADY := f-b1.5-y3-c3-p1.3
RCF_RUNS ?= $(if $(MINI),$(RCF_STEADY) f-b1.5-y3-c3-p1.3-h10 f-b1.5-y3-c3-p1.0 f-b1.5-y3-c3-p1.2-tough-damp, \
  $(RCF_STEADY) $(foreach y,2 2.5 3.5,f-b1.5-y$(y)-c$(y)-p1.3) f-b1-y3-c3-p1.3 f-b0.5-y3-c3-p1.3 \
  $(foreach b,1.5 1 0.5,$(foreach y,4 3.5 3 2.5,f-b$(b)-y$(y)-c4-p1.3)) \
  f-b1.5-y3-c3-p1.3-h40 f-b1.5-y3-c3-p1.3-h160 \
  $(foreach p,1.0 1.1 1.2,f-b1.5-y3-c3-p$(p)) f-b1.5-y3-c3-p1.3-tough f-b1.5-y3-c3-p1.2-damp \
  f-b1.5-y3-c3-p1.2-tough-damp f-b1.5-y3-c3-p1.1-tough-damp)
# The heights the runs ask for (h<rows>), and the default.
RCF_HEIGHTS := $(sort $(RCF_ROWS) $(patsubst h%,%,$(filter h%,$(subst -, ,$(RCF_RUNS)))))
RCF_MESHES := $(foreach h,$(RCF_HEIGHTS),$(RC)/strip-$(RCF_LENGTH)x$(h).h5)

$(RC)/strip-%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen triangular --nodes $* --spacing 1e-3 -q -o $@

# rcf_field,NAME,LETTER: the value of the field LETTER<value> of a run name; rcf_flag,NAME,WORD: WORD if present.
rcf_field = $(patsubst $(2)%,%,$(filter $(2)%,$(subst -, ,$(1))))
rcf_flag = $(filter $(2),$(subst -, ,$(1)))
$(RC)/f-%.h5: $(RCF_MESHES) $(RC_SCENE) | build
	@echo "rubber-run freeze $*"
	@uc=$$(awk -v l=$(call rcf_field,$*,c) 'BEGIN { printf "%.6g", 1e-3 * (sqrt(0.36 + 0.75 * l * l) + 0.134) }'); \
	 $(RUN_ENV) $(LAUNCH) $(BIN)/rubber-run $(THREADS_OPT) --scene $(RC_SCENE) \
	   $(RC)/strip-$(RCF_LENGTH)x$(or $(call rcf_field,$*,h),$(RCF_ROWS)).h5 $(RCF_COMMON) \
	   --material.b $(call rcf_field,$*,b) --loading.stretch_y $(call rcf_field,$*,y) --law.cutoff_length $$uc \
	   --crack.path_cutoff_ratio $(call rcf_field,$*,p) $(if $(call rcf_flag,$*,tough),$(RCF_tough)) \
	   $(if $(call rcf_flag,$*,damp),$(RCF_damp)) -o $@ 2> $(@:.h5=.log)

$(RC)/frow-%.csv: $(RC)/f-%.h5 scripts/rubber-crack-row.sh
	@bash scripts/rubber-crack-row.sh $(BIN) $< $* > $@

$(RC)/freeze.csv: $(foreach r,$(RCF_RUNS),$(RC)/frow-$(patsubst f-%,%,$(r)).csv)
	@{ bash scripts/rubber-crack-row.sh --header; cat $^; } > $@

# Two tables over the same runs: the speeds, then the shape and the wake.
$(RC)/freeze.md: $(RC)/freeze.csv
	@{ echo "# rubber-crack: energy-neutral failure with a crack path ($(RCF_LENGTH) × $(RCF_ROWS) nodes unless h says, λx = 1.2, t_max = $(RCF_TMAX) s)"; echo; \
	   echo "Runs f-b<b>-y<λy>-c<λc>-p<ratio>[-tough][-damp][-h<rows>]: u_c = u_0(λc) + 0.134Δ; speed fitted after the first 50Δ; windows: the slope over each 0.1 ms against it."; echo; \
	   echo "| run | b | λy | u_c − u_0 (Δ) | path ratio | advance after 50Δ (Δ) | v (m/s) | 0.1 ms windows (%) | c_T | c_L | v/c_T | v/c_L | outcome |"; \
	   echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"; \
	   tail -n +2 $< | awk -F, '{ printf "| %s | %s | %s | %.3g | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $$1, $$2, $$3, $$6 - $$5, \
	     $$7 + 0, $$11, $$12, $$13 == "" ? "" : $$13 " … " $$14, $$15, $$16, $$17, $$18, $$28 }'; echo; \
	   echo "Shape (the frame where the tip passes 60 % of the strip, or the final one): the angle to the crack line of the front behind which the sheet lets go, against the Mach angles at the tip's speed (longitudinal and transverse, v sin α = c(n), and asin(c_L,x/v)); lag: tip minus the front's intercept on the crack line; grips: bonds from the clamped rows behind the tip broken, and debris: free nodes flung past the grips (further than a half strip folded over its grip reaches)."; echo; \
	   echo "| run | front angle (°) | Mach L (°) | asin(c_L,x/v) (°) | Mach T (°) | lag (Δ) | bulk bonds broken | grip bonds broken (%) | debris (% of nodes) | ΔE/E (%) |"; \
	   echo "|---|---|---|---|---|---|---|---|---|---|"; \
	   tail -n +2 $< | awk -F, '{ printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $$1, $$20, $$21, $$22, $$23, $$24, $$25, $$26, $$27, $$19 }'; } > $@

# Bonds coloured by strain around the tip, halfway through the steady run, and the same with toughening and
# damping: the wedge, its Mach lines and the debris behind it.
rcf_picture = t=$$(awk -v t=$(RCF_TMAX) 'BEGIN { print t / 2 }'); \
	tip=$$($(BIN)/observables $< --crack-shape --time $$t -q | awk '$$1 == "tip_x" { print $$2 }'); \
	$(LAUNCH) $(BIN)/render $< --time $$t --colour strain --beams strain --axes -q --width 800 \
	  --view $$(awk -v x=$$tip -v h=$(RCF_ROWS) 'BEGIN { printf "%g,%g,%g,%g", x - 0.16 * h / 80, -0.03 * h / 80, x + 0.04 * h / 80, 0.235 * h / 80 }') -o $@
$(RC)/crack.png: $(RC)/$(RCF_STEADY).h5
	@$(rcf_picture)
$(RC)/crack-toughened.png: $(RC)/f-b1.5-y3-c3-p1.2-tough-damp.h5
	@$(rcf_picture)
