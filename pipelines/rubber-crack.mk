# rubber-crack: a crack seeded from the left edge of a strip pre-stretched to (λx, λy), Marder's rubber lattice
# (physics/rubber-lattice.md §6, rubber-lattice-validation.md §D). Each lever the issue names is a separate
# switch of data/scenes/stretch.ini; every run records how far the tip went, its speed over the last stretch of
# advance (λx × reference tip x, fitted), the lattice's own c_T and c_L along x at the run's law, the energy
# balance and the bonds past u_c. Ends in results/rubber-crack/table.{csv,md} and a snapshot of the run that
# went furthest. docs/rubber-run.md discusses the outcome.
#   make -f Makefile.analysis rubber-crack [RC_NODES=300x60] [RC_TMAX=2e-3] [JOBS=2]
# MINI=1 (the end-to-end test): a 60 × 16 strip for 4 time units, two levers and one stretch.
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
RC_LEVERS ?= $(if $(MINI),paper weight,paper irreversible damped near-failure toughened c1 kick soft soft-all weight \
             weight-uc10 weight-soft weight-ramp pair-only three-body-0.02 three-body-0.05 three-body-0.1 \
             three-body-0.25)
# The stretch across the crack, with the softening law placed 0.02Δ + L above each far field.
RC_STRETCHES ?= $(if $(MINI),3,2.5 3 3.5)
# The pair law alone across stretches, u_c 0.134Δ above each far field.
RC_PAIR_STRETCHES ?= $(if $(MINI),,2 2.5 3.5)

RC_RUNS := $(foreach l,$(RC_LEVERS),$(RC)/lever-$(l).h5) $(foreach s,$(RC_STRETCHES),$(RC)/stretch-$(s).h5) \
           $(foreach s,$(RC_PAIR_STRETCHES),$(RC)/pair-stretch-$(s).h5)

.PHONY: rubber-crack
rubber-crack: $(RC)/table.md $(RC)/snapshot.png
	@cat $(RC)/table.md

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
