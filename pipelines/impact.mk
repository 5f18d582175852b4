# impact: Kun et al. 1999 §3.3.2, Figs. II and 12 (physics/polygon-dem.md §8.4).
# A 0.40 m × 0.20 m block of 40 × 20 cells; the cell at the middle of the bottom layer flies into it at
# 400 m/s. Snapshots at 4e-4, 1.5e-3 and 3e-3 s, the fragment mass histogram pooled over seeds, and β.
#   make -f Makefile.analysis impact [SEEDS='1 2 3'] [JOBS=2]
IM := $(RESULTS)/impact
IM_S1 := $(firstword $(SEEDS))
IM_CELLS := $(if $(MINI),20x10,40x20)
IM_RUN_OPTIONS := $(if $(MINI),--stop.t_max 1e-3 --output.frame_interval 2e-4,)
IM_FIT_OPTIONS := $(if $(MINI),--bootstrap 20 --gof-samples 20 --min-tail 5,--bootstrap 100 --gof-samples 100)

.PHONY: impact
impact: $(IM)/table.md $(IM)/histogram.png $(IM)/snapshots
	@cat $(IM)/table.md

$(IM)/mesh-s%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape rect --size 0.40x0.20 --cells $(IM_CELLS) --seed $* -q -o $@

$(IM)/run-s%.h5: $(IM)/mesh-s%.h5 data/scenes/impact.ini | build
	@echo "dem-run impact seed $*"
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/impact.ini $< -q -o $@ $(IM_RUN_OPTIONS)

$(IM)/frag-s%.h5: $(IM)/run-s%.h5
	$(BIN)/fragment-count $< --min-cells 2 -q -o $@

$(IM)/fit.txt: $(foreach s,$(SEEDS),$(IM)/frag-s$(s).h5)
	$(BIN)/powerlaw-fit $^ --column mass $(IM_FIT_OPTIONS) --format text \
	  --histogram-csv $(IM)/histogram.csv -q -o $@

$(IM)/ours.csv: $(IM)/fit.txt $(IM)/run-s$(IM_S1).h5
	@{ echo "quantity,value,error"; \
	   awk '{ v[$$1] = $$2 } END { printf "beta,%.4g,%.2g\n", v["alpha"], v["alpha_stderr"] }' $<; \
	   echo "impactor_energy_J,$$($(BIN)/observables $(word 2,$^) --parameter derived.kick_kinetic_energy),"; \
	   echo "impactor_speed_m_s,$$($(BIN)/observables $(word 2,$^) --parameter derived.kick_mean_speed),"; } > $@

$(IM)/table.md: $(IM)/ours.csv $(IM)/fit.txt data/reference/impact.csv
	@{ echo "# Projectile impact on a block (Kun et al. 1999 Figs. II, 12)"; echo; \
	   echo "$(IM_CELLS) cells in 0.40 m × 0.20 m, one cell of 457 J into it (the paper: 400 m/s, ≈ 457 J; speed below), t_ε = 3 %, t_Θ = 4°, seeds pooled: $(SEEDS);"; \
	   echo "single cells left out; β = α of the maximum-likelihood fit of F(m) ~ m^-β."; echo; \
	   awk -F, -f scripts/compare.awk data/reference/impact.csv $<; echo; \
	   echo '```'; grep -E '^(alpha|alpha_stderr|alpha_bootstrap_std|xmin|n_tail|gof_p|logbin_alpha|logbin_alpha_stderr|lr_)' $(IM)/fit.txt; echo '```'; } > $@

$(IM)/histogram.png: $(IM)/fit.txt pipelines/plots/histogram.gp
	@gnuplot -e "csv='$(IM)/histogram.csv'; out='$(IM)/histogram'; title='impact, seeds $(SEEDS)'" pipelines/plots/histogram.gp

$(IM)/snapshots: $(IM)/run-s$(IM_S1).h5 $(IM)/frag-s$(IM_S1).h5
	@mkdir -p $@
	@for t in 4e-4 1.5e-3 3e-3; do $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $@/impact-$$t.png; \
	  $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $@/impact-$$t.svg; done
	@$(BIN)/render $< --fragments $(word 2,$^) --beams off -q -o $@/fragments.png
	@touch $@
