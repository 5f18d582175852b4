# demo: the explosion of Kun et al. 1999 (§3.3.1, Figs. 1 and 11) at paper scale with one seed: the
# README's main-job command. A 0.4 m disc of 1100 cells, E0 = 500 J, t_ε = 3 %, t_Θ = 4°, Table 1 values
# (data/scenes/explosion.ini); then fragments, the power-law fit of their masses and pictures.
#   make -f Makefile.analysis demo [DEMO_SEED=7]
# Writes results/demo/: explosion.h5 (+ .xdmf for ParaView), fragments.h5, fit.txt, histogram.{csv,png},
# explosion-{1e-4,1e-3,4e-3}.png, fragments.png and summary.md.
DEMO := $(RESULTS)/demo
DEMO_SEED ?= 7
DEMO_CELLS := $(if $(MINI),300,1100)
DEMO_RUN_OPTIONS := $(if $(MINI),--stop.t_max 1e-3 --output.frame_interval 2e-4,)

.PHONY: demo
demo: $(DEMO)/summary.md $(DEMO)/pictures
	@cat $(DEMO)/summary.md

$(DEMO)/disc.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.40 --cells $(DEMO_CELLS) --seed $(DEMO_SEED) -q -o $@

# The run: progress on stderr, a line every few seconds (about 5 s on one core).
$(DEMO)/explosion.h5: $(DEMO)/disc.h5 data/scenes/explosion.ini | build
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/explosion.ini $< --seed $(DEMO_SEED) -o $@ $(DEMO_RUN_OPTIONS) \
	  2>&1 | tee $(DEMO)/explosion.log
	$(BIN)/h5-xdmf $@ -q

$(DEMO)/fragments.h5: $(DEMO)/explosion.h5
	$(BIN)/fragment-count $< --min-cells 2 -q -o $@

$(DEMO)/fit.txt: $(DEMO)/fragments.h5
	$(BIN)/powerlaw-fit $< --column mass --bootstrap 200 --gof-samples 200 --format text \
	  --histogram-csv $(DEMO)/histogram.csv -q -o $@

$(DEMO)/summary.md: $(DEMO)/fit.txt $(DEMO)/explosion.h5 data/reference/explosion.csv
	@{ echo "# Demo: explosion of a disc (Kun et al. 1999, t_ε = 3 %, t_Θ = 4°, one seed: $(DEMO_SEED))"; echo; \
	   echo "$(DEMO_CELLS) cells in a 0.4 m disc, E0 = 500 J (h = 1 cm). β: maximum-likelihood exponent of the"; \
	   echo "fragment mass density F(m) ~ m^-β over fragments of at least 2 cells (one seed: expect a wide error;"; \
	   echo "make -f Makefile.analysis explosion pools seeds over the paper's parameter sweep)."; echo; \
	   echo "| quantity | value |"; echo "|---|---|"; \
	   awk '{ v[$$1] = $$2 } END { printf "| β (MLE) | %.3f ± %.2f (bootstrap σ %.2f) |\n| x_min (kg) | %.3g |\n| fragments in the tail | %d |\n| β (log-binned) | %.3f ± %.2f |\n| paper | 2.0 ± 0.05 (Fig. 11) |\n", \
	     v["alpha"], v["alpha_stderr"], v["alpha_bootstrap_std"], v["xmin"], v["n_tail"], v["logbin_alpha"], v["logbin_alpha_stderr"] }' $<; \
	   echo "| kick: mean speed (m/s) | $$($(BIN)/observables $(word 2,$^) --parameter derived.kick_mean_speed) |"; \
	   echo "| kick: total momentum / scale | $$($(BIN)/observables $(word 2,$^) --parameter derived.kick_momentum_over_scale) |"; \
	   echo "| run | $$(tail -n 1 $(DEMO)/explosion.log | sed 's/^dem-run: //; s/|/∣/g') |"; \
	   echo; echo "Pictures: explosion-1e-4.png, explosion-1e-3.png, explosion-4e-3.png (beams coloured by strain / t_ε,"; \
	   echo "cells by speed), fragments.png (cells coloured by fragment), histogram.png (F(m) with the fit)."; } > $@

$(DEMO)/histogram.png: $(DEMO)/fit.txt pipelines/plots/histogram.gp
	@gnuplot -e "csv='$(DEMO)/histogram.csv'; out='$(DEMO)/histogram'; title='explosion demo, seed $(DEMO_SEED)'" pipelines/plots/histogram.gp

$(DEMO)/pictures: $(DEMO)/explosion.h5 $(DEMO)/fragments.h5 $(DEMO)/histogram.png
	@for t in 1e-4 1e-3 4e-3; do $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $(DEMO)/explosion-$$t.png; done
	@$(BIN)/render $< --fragments $(word 2,$^) --beams off -q -o $(DEMO)/fragments.png
	@touch $@
