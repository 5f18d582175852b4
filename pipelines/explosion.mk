# explosion: Kun et al. 1999 §3.3.1, Figs. 1, 10, 11 (physics/polygon-dem.md §8.3).
# A disc of 1100 cells (0.4 m) exploded from its centre with E0 = 500 J: snapshots (Fig. 1), the elastic
# pulse with breaking off (Fig. 10), fragment mass histograms pooled over seeds for t_ε = 1…6 % at
# t_Θ = 4° and t_Θ = 1…7° at t_ε = 3 % (Fig. 11), β per parameter pair by both estimators (the
# maximum-likelihood fit, and the paper's slope of the log-binned F(m) over 2 … 25 cells with its error from
# the seed-to-seed spread), and the largest fragment's share of the mass against E0 per mass.
#   make -f Makefile.analysis explosion [EX_SEEDS='1 2 3'] [JOBS=2]
EX := $(RESULTS)/explosion
# 8 seeds a parameter pair: the seed-to-seed error of the log-binned slope is then about 0.05.
EX_SEEDS ?= $(if $(MINI),1 2,$(shell seq 1 8))
# The paper's estimator over the decade above the single cells, as for the impact (pipelines/impact.mk).
EX_LOGBIN := --logbin-min 2cells --logbin-max 25cells
# E0 scan at t_ε = 3 %, t_Θ = 4°: 1/4 … 8 times 500 J, 4 seeds each (500 J: the sweep's runs).
EX_ENERGIES := $(if $(MINI),1000 2000 4000,125 250 1000 2000 4000)
EX_SCAN_SEEDS ?= $(if $(MINI),1 2,$(wordlist 1,4,$(EX_SEEDS)))
EX_TEPS := $(if $(MINI),2 3,1 2 3 4 5 6)
EX_TTHETA := $(if $(MINI),4,1 2 3 4 5 6 7)
EX_CELLS := $(if $(MINI),300,1100)
EX_RUN_OPTIONS := $(if $(MINI),--stop.t_max 1e-3 --output.frame_interval 2e-4,)
EX_FIT_OPTIONS := $(EX_LOGBIN) $(if $(MINI),--bootstrap 20 --gof-samples 20 --min-tail 5,--bootstrap 100 --gof-samples 100)
# Parameter pairs as teps-ttheta (percent, degrees); 3-4 is in both sweeps.
EX_PAIRS := $(sort $(foreach e,$(EX_TEPS),$(e)-4) $(foreach t,$(EX_TTHETA),3-$(t)))

.PHONY: explosion
explosion: $(EX)/table.md $(EX)/histograms.png $(EX)/largest.png $(EX)/snapshots $(EX)/pulse
	@cat $(EX)/table.md

$(EX)/mesh-s%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.40 --cells $(EX_CELLS) --seed $* -q -o $@

# runs/<teps>-<ttheta>-s<seed>.h5 (E0 = 500 J) and energy/run-<E0>-s<seed>.h5 (t_ε = 3 %, t_Θ = 4°)
.SECONDEXPANSION:
$(EX)/runs/%.h5: $$(EX)/mesh-$$(lastword $$(subst -, ,$$*)).h5 data/scenes/explosion.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r teps ttheta seed <<< "$*"; echo "dem-run explosion t_eps $$teps % t_theta $$ttheta° $$seed"; \
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/explosion.ini $< -q -o $@ \
	  --material.t_eps $$(awk -v p=$$teps 'BEGIN { print p / 100 }') --material.t_theta_deg $$ttheta $(EX_RUN_OPTIONS)

$(EX)/runs/%.frag.h5: $(EX)/runs/%.h5
	$(BIN)/fragment-count $< --min-cells 2 -q -o $@

$(EX)/energy/run-%.h5: $$(EX)/mesh-$$(lastword $$(subst -, ,$$*)).h5 data/scenes/explosion.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r energy seed <<< "$*"; echo "dem-run explosion E0 $$energy J $$seed"; \
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/explosion.ini $< -q -o $@ \
	  --loading.energy $$energy $(EX_RUN_OPTIONS)

$(EX)/energy/frag-%.h5: $(EX)/energy/run-%.h5
	$(BIN)/fragment-count $< --min-cells 2 -q -o $@

# Pooled over seeds, per parameter pair: both estimators and their spread over seeds (key value lines), and
# the log-binned histogram.
$(EX)/fits/%.txt: $$(foreach s,$$(EX_SEEDS),$$(EX)/runs/$$*-s$$(s).frag.h5)
	@mkdir -p $(@D)
	$(BIN)/powerlaw-fit $^ --column mass $(EX_FIT_OPTIONS) --format text \
	  --histogram-csv $(EX)/fits/$*.hist.csv -q -o $@

$(EX)/betas.csv: $(foreach p,$(EX_PAIRS),$(EX)/fits/$(p).txt) scripts/fit-row.awk
	@{ echo "t_eps_percent,t_theta_deg,seeds,$$(awk -v header=1 -f scripts/fit-row.awk < /dev/null)"; \
	  for f in $(filter %.txt,$^); do p=$$(basename $$f .txt); \
	    echo "$${p%-*},$${p#*-},$(words $(EX_SEEDS)),$$(awk -f scripts/fit-row.awk $$f)"; \
	  done; } > $@

# m_max / M per E0: the sweep's 3-4 runs at 500 J and the scan, mean ± standard error over seeds.
EX_SCAN_FRAGS = $(foreach e,$(EX_ENERGIES),$(foreach s,$(EX_SCAN_SEEDS),$(EX)/energy/frag-$(e)-s$(s).h5))
$(EX)/largest.csv: $(EX_SCAN_FRAGS) $(foreach s,$(EX_SCAN_SEEDS),$(EX)/runs/3-4-s$(s).frag.h5) scripts/largest-share.sh
	@{ bash scripts/largest-share.sh --header; \
	  for e in $$(tr ' ' '\n' <<< "500 $(EX_ENERGIES)" | sort -n); do \
	    if [[ $$e == 500 ]]; then bash scripts/largest-share.sh $$e $(foreach s,$(EX_SCAN_SEEDS),$(EX)/runs/3-4-s$(s).frag.h5); \
	    else bash scripts/largest-share.sh $$e $(foreach s,$(EX_SCAN_SEEDS),$(EX)/energy/frag-$$e-s$(s).h5); fi; \
	  done; } > $@

# The exponent of m_max/M ~ (E0/M)^-λ over the fragmented points (m_max/M < 0.5) up to the smallest m_max/M,
# equal weights (as pipelines/impact.mk).
$(EX)/largest-fit.txt: $(EX)/largest.csv scripts/loglog-fit.awk
	@awk -F, -v x=2 -v y=4 -v ymax=0.5 -v to_min=1 -f scripts/loglog-fit.awk $< > $@

$(EX)/largest.png: $(EX)/largest.csv $(EX)/largest-fit.txt pipelines/plots/largest.gp
	@gnuplot -e "csv='$<'; fit='$(word 2,$^)'; xlabel='explosion energy per mass E_0/M (J/kg)'; \
	  title='explosion: largest fragment'; out='$(EX)/largest'" pipelines/plots/largest.gp

# The explosion's initial kick (validation B1-B3), measured on the first seed's 3-4 run.
EX_S1 := $(firstword $(EX_SEEDS))
$(EX)/kick.csv: $(EX)/runs/3-4-s$(EX_S1).h5
	@$(BIN)/observables $< --columns kinetic_energy_translational | grep -v '^#' | sed -n 2p | \
	  awk -F, '{ printf "kinetic_energy_J,%s\n", $$2 }' > $@
	@for k in mean_speed momentum_over_scale; do echo "kick_$$k,$$($(BIN)/observables $< --parameter derived.kick_$$k)"; done >> $@

# Columns of betas.csv (scripts/fit-row.awk after t_eps, t_theta, seeds): 5 β MLE, 7 bootstrap σ,
# 13 β log-binned, 14 its jackknife error. The spread over the sweep leaves out t_ε = 1 % and t_Θ = 1°, the
# "extremely small breaking parameters" the paper excepts.
$(EX)/ours.csv: $(EX)/betas.csv $(EX)/kick.csv $(EX)/largest-fit.txt
	@awk -F, '/^#/ || FNR == 1 && FILENAME ~ /betas/ { next } \
	  FILENAME ~ /betas/ { if ($$1 == 3 && $$2 == 4) { bm = $$5; em = $$7; bl = $$13; el = $$14 } \
	    if ($$1 == 1 || $$2 == 1) next; \
	    lo_m = (lo_m == "" || $$5 < lo_m) ? $$5 : lo_m; hi_m = $$5 > hi_m ? $$5 : hi_m; \
	    lo_l = (lo_l == "" || $$13 < lo_l) ? $$13 : lo_l; hi_l = $$13 > hi_l ? $$13 : hi_l; next } \
	  FILENAME ~ /kick/ { split($$0, kv, ","); k[kv[1]] = kv[2]; next } \
	  { split($$0, kv, " "); f[kv[1]] = kv[2] } \
	  END { print "quantity,value,error"; printf "beta_logbin_te3_tt4,%s,%s\nbeta_mle_te3_tt4,%s,%s\n", bl, el, bm, em; \
	    printf "beta_logbin_spread_over_sweep,%.4g,\nbeta_mle_spread_over_sweep,%.4g,\n", hi_l - lo_l, hi_m - lo_m; \
	    printf "largest_share_exponent,%s,%s\n", f["exponent"], f["exponent_stderr"]; \
	    printf "kick_momentum_over_p_scale,%s,\n", k["kick_momentum_over_scale"]; \
	    printf "mean_kicked_speed_m_per_s,%s,\n", k["kick_mean_speed"] }' $(EX)/betas.csv $(EX)/kick.csv $(EX)/largest-fit.txt > $@

$(EX)/table.md: $(EX)/ours.csv $(EX)/betas.csv $(EX)/largest.csv $(EX)/largest-fit.txt data/reference/explosion.csv
	@{ echo "# Explosion of a disc (Kun et al. 1999 Figs. 1, 10, 11)"; echo; \
	   echo "$(EX_CELLS) cells in a 0.4 m disc, E0 = 500 J (h = 1 cm), seeds pooled: $(EX_SEEDS); single cells left out. β of"; \
	   echo "F(m) ~ m^-β by two estimators: the maximum-likelihood fit (x_min by minimum KS distance, bootstrap σ,"; \
	   echo "goodness-of-fit p; per seed: mean ± SE) and the paper's, the weighted slope of the log-binned F(m) over"; \
	   echo "fragments of 2 … 25 cells (bins between the cell-count clusters), pooled ± its jackknife error over seeds"; \
	   echo "(per seed: mean ± SE)."; echo; \
	   awk -F, -f scripts/compare.awk data/reference/explosion.csv $<; echo; \
	   echo "| t_ε (%) | t_Θ (°) | fragments | β MLE ± σ_boot | x_min (cells) | n_tail | GoF p | MLE per seed | β log-binned ± jackknife | χ²/dof | log-binned per seed |"; \
	   echo "|---|---|---|---|---|---|---|---|---|---|---|"; \
	   awk -F, '/^#/ || NR == 1 { next } { for (i = 1; i <= NF; i++) if ($$i == "") $$i = "–"; \
	     printf "| %s | %s | %s | %s ± %s | %s | %s | %s | %s ± %s | %s ± %s | %s | %s ± %s |\n", \
	       $$1, $$2, $$4, $$5, $$7, $$8, $$9, $$10, $$11, $$12, $$13, $$14, $$15, $$16, $$17 }' $(EX)/betas.csv; echo; \
	   echo "Largest fragment against the explosion energy per mass (t_ε = 3 %, t_Θ = 4°, seeds $(EX_SCAN_SEEDS)):"; echo; \
	   echo "| E0 (J) | E0/M (J/kg) | seeds | m_max/M |"; echo "|---|---|---|---|"; \
	   awk -F, '/^#/ || NR == 1 { next } { printf "| %s | %s | %s | %s ± %s |\n", $$1, $$2, $$3, $$4, $$5 }' $(EX)/largest.csv; echo; \
	   awk '{ v[$$1] = $$2 } END { printf "m_max/M ~ (E0/M)^%s ± %s (least squares of the logs) over the %d points from\n", \
	     v["exponent"], v["exponent_stderr"], v["points"]; \
	     printf "E0/M = %s to %s J/kg: m_max/M < 0.5, up to its minimum.\n", v["x_min"], v["x_max"] }' $(EX)/largest-fit.txt; } > $@

$(EX)/histograms.png: $(EX)/betas.csv pipelines/plots/histograms.gp
	@gnuplot -e "dir='$(EX)/fits'; teps='$(EX_TEPS)'; ttheta='$(EX_TTHETA)'; out='$(EX)/histograms'" pipelines/plots/histograms.gp

# Snapshots of the first seed's base run at 1e-4, 1e-3 and 4e-3 s, beams coloured by strain / t_ε (Fig. 1).
$(EX)/snapshots: $(EX)/runs/3-4-s$(EX_S1).h5 $(EX)/runs/3-4-s$(EX_S1).frag.h5
	@mkdir -p $@
	@for t in 1e-4 1e-3 4e-3; do $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $@/explosion-$$t.png; \
	  $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $@/explosion-$$t.svg; done
	@$(BIN)/render $< --fragments $(word 2,$^) --beams off -q -o $@/fragments.png
	@touch $@

# The elastic pulse with breaking off (Fig. 10): snapshots at 1e-4, 3e-4 and 5e-4 s.
$(EX)/pulse.h5: $(EX)/mesh-s$(EX_S1).h5 data/scenes/pulse.ini | build
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/pulse.ini $< -q -o $@ $(if $(MINI),--stop.t_max 2e-4,)

$(EX)/pulse: $(EX)/pulse.h5
	@mkdir -p $@
	@for t in 1e-4 3e-4 5e-4; do $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $@/pulse-$$t.png; done
	@touch $@
