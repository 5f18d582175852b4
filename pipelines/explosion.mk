# explosion: Kun et al. 1999 §3.3.1, Figs. 1, 10, 11 (physics/polygon-dem.md §8.3).
# A disc of 1100 cells (0.4 m) exploded from its centre with E0 = 500 J: snapshots (Fig. 1), the elastic
# pulse with breaking off (Fig. 10), fragment mass histograms pooled over seeds for t_ε = 1…6 % at
# t_Θ = 4° and t_Θ = 1…7° at t_ε = 3 % (Fig. 11), and β per parameter pair.
#   make -f Makefile.analysis explosion [SEEDS='1 2 3'] [JOBS=2]
EX := $(RESULTS)/explosion
EX_TEPS := $(if $(MINI),2 3,1 2 3 4 5 6)
EX_TTHETA := $(if $(MINI),4,1 2 3 4 5 6 7)
EX_CELLS := $(if $(MINI),300,1100)
EX_RUN_OPTIONS := $(if $(MINI),--stop.t_max 1e-3 --output.frame_interval 2e-4,)
EX_FIT_OPTIONS := $(if $(MINI),--bootstrap 20 --gof-samples 20 --min-tail 5,--bootstrap 100 --gof-samples 100)
# Parameter pairs as teps-ttheta (percent, degrees); 3-4 is in both sweeps.
EX_PAIRS := $(sort $(foreach e,$(EX_TEPS),$(e)-4) $(foreach t,$(EX_TTHETA),3-$(t)))
EX_RUNS := $(foreach p,$(EX_PAIRS),$(foreach s,$(SEEDS),$(EX)/runs/$(p)-s$(s)))

.PHONY: explosion
explosion: $(EX)/table.md $(EX)/histograms.png $(EX)/snapshots $(EX)/pulse
	@cat $(EX)/table.md

$(EX)/mesh-s%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.40 --cells $(EX_CELLS) --seed $* -q -o $@

# runs/<teps>-<ttheta>-s<seed>.h5
.SECONDEXPANSION:
$(EX)/runs/%.h5: $$(EX)/mesh-$$(lastword $$(subst -, ,$$*)).h5 data/scenes/explosion.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r teps ttheta seed <<< "$*"; echo "dem-run explosion t_eps $$teps % t_theta $$ttheta° $$seed"; \
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/explosion.ini $< -q -o $@ \
	  --material.t_eps $$(awk -v p=$$teps 'BEGIN { print p / 100 }') --material.t_theta_deg $$ttheta $(EX_RUN_OPTIONS)

$(EX)/runs/%.frag.h5: $(EX)/runs/%.h5
	$(BIN)/fragment-count $< --min-cells 2 -q -o $@

# Pooled over seeds, per parameter pair: the fit (key value lines) and the log-binned histogram.
$(EX)/fits/%.txt: $$(foreach s,$$(SEEDS),$$(EX)/runs/$$*-s$$(s).frag.h5)
	@mkdir -p $(@D)
	$(BIN)/powerlaw-fit $^ --column mass $(EX_FIT_OPTIONS) --format text \
	  --histogram-csv $(EX)/fits/$*.hist.csv -q -o $@

$(EX)/betas.csv: $(foreach p,$(EX_PAIRS),$(EX)/fits/$(p).txt)
	@{ echo "t_eps_percent,t_theta_deg,beta_mle,beta_mle_stderr,beta_bootstrap_std,xmin_kg,n_tail,gof_p,beta_logbin,beta_logbin_stderr"; \
	  for f in $^; do p=$$(basename $$f .txt); \
	    awk -v p="$$p" '{ v[$$1] = $$2 } END { split(p, a, "-"); \
	      printf "%s,%s,%.4g,%.2g,%.2g,%.4g,%d,%.3g,%.4g,%.2g\n", a[1], a[2], v["alpha"], v["alpha_stderr"], \
	        v["alpha_bootstrap_std"], v["xmin"], v["n_tail"], v["gof_p"], v["logbin_alpha"], v["logbin_alpha_stderr"] }' $$f; \
	  done; } > $@

# The explosion's initial kick (validation B1-B3), measured on the first seed's 3-4 run.
EX_S1 := $(firstword $(SEEDS))
$(EX)/kick.csv: $(EX)/runs/3-4-s$(EX_S1).h5
	@$(BIN)/observables $< --columns kinetic_energy_translational | grep -v "^#" | sed -n 2p | \
	  awk -F, '{ printf "kinetic_energy_J,%s\n", $$2 }' > $@
	@for k in mean_speed momentum_over_scale; do echo "kick_$$k,$$($(BIN)/observables $< --parameter derived.kick_$$k)"; done >> $@

$(EX)/ours.csv: $(EX)/betas.csv $(EX)/kick.csv
	@awk -F, 'FNR == 1 { next } FILENAME ~ /betas/ { if ($$1 == 3 && $$2 == 4) { b = $$3; e = $$4 } \
	    if (min == "" || $$3 < min) min = $$3; if (max == "" || $$3 > max) max = $$3; next } \
	  { k[$$1] = $$2 } \
	  END { print "quantity,value,error"; printf "beta_te3_tt4,%s,%s\n", b, e; \
	    printf "beta_spread_over_sweep,%.4g,\n", max - min; \
	    printf "kick_momentum_over_p_scale,%s,\n", k["kick_momentum_over_scale"]; \
	    printf "mean_kicked_speed_m_per_s,%s,\n", k["kick_mean_speed"] }' $(EX)/betas.csv $(EX)/kick.csv > $@

$(EX)/table.md: $(EX)/ours.csv $(EX)/betas.csv data/reference/explosion.csv
	@{ echo "# Explosion of a disc (Kun et al. 1999 Figs. 1, 10, 11)"; echo; \
	   echo "$(EX_CELLS) cells in a 0.4 m disc, E0 = 500 J (h = 1 cm), seeds pooled: $(SEEDS); single cells left out; β = α of the"; \
	   echo "maximum-likelihood fit of the density F(m) ~ m^-β (x_min by minimum KS distance), the log-binned slope beside it."; echo; \
	   awk -F, -f scripts/compare.awk data/reference/explosion.csv $<; echo; \
	   echo "| t_ε (%) | t_Θ (°) | β (MLE) | bootstrap σ | x_min (kg) | n_tail | GoF p | β (log-binned) |"; echo "|---|---|---|---|---|---|---|---|"; \
	   awk -F, 'NR > 1 { printf "| %s | %s | %s ± %s | %s | %s | %s | %s | %s ± %s |\n", $$1, $$2, $$3, $$4, $$5, $$6, $$7, $$8, $$9, $$10 }' $(EX)/betas.csv; } > $@

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
