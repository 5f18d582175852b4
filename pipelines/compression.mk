# compression: Kun et al. 1999 §3.2, Figs. 7-9 (physics/polygon-dem.md §8.2).
# 25 × 40 cells; top and bottom layers driven inward with x and rotation fixed; sides free; breaking on.
# σ(ε) with the failure strain at its peak, and the broken beams at three times.
#   make -f Makefile.analysis compression [CC_SEEDS='1 2 3']
CC := $(RESULTS)/compression
CC_SEEDS ?= $(firstword $(SEEDS))
CC_CELLS := $(if $(MINI),10x16,25x40)
# Broken-beam maps (Fig. 8) at these times, s: before (ε ≈ 2.4 %), just after (2.7 %) the stress peak, and the end.
CC_MAP_TIMES := 0.025 0.028 0.03

.PHONY: compression
compression: $(CC)/table.md $(CC)/stress-strain.png $(CC)/broken-maps
	@cat $(CC)/table.md

$(CC)/mesh-s%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape rect --size 0.25x0.40 --cells $(CC_CELLS) --seed $* -q -o $@

$(CC)/run-s%.h5: $(CC)/mesh-s%.h5 data/scenes/confined-compression.ini | build
	@echo "dem-run confined-compression seed $*"
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/confined-compression.ini $< -q -o $@

# σ(ε) per seed, compression positive (the paper plots it so).
$(CC)/curve-s%.csv: $(CC)/run-s%.h5
	@{ echo "strain,stress_Pa,intact_beams"; \
	   $(BIN)/observables $< --columns axial_strain,stress,intact_beams | grep -v "^#" | tail -n +2 | \
	   awk -F, '{ printf "%.6g,%.6g,%d\n", -$$2, -$$3, $$4 }'; } > $@

# Per seed: failure strain (at the stress peak), peak stress, drop after the peak, broken fraction.
$(CC)/peak-s%.csv: $(CC)/curve-s%.csv
	@awk -F, 'NR == 2 { b0 = $$3 } NR > 1 { if ($$2 > smax) { smax = $$2; emax = $$1 } last = $$2; b = $$3 } \
	  END { printf "%s,%.6g,%.6g,%.4f,%.4f\n", "$*", emax, smax, 1 - last / smax, 1 - b / b0 }' $< > $@

$(CC)/peaks.csv: $(foreach s,$(CC_SEEDS),$(CC)/peak-s$(s).csv)
	@{ echo "seed,failure_strain,peak_stress_Pa,post_peak_stress_drop,broken_fraction"; cat $^; } > $@

$(CC)/ours.csv: $(CC)/peaks.csv
	@awk -F, 'NR > 1 { n++; e += $$2; ee += $$2 * $$2; d += $$4; b += $$5 } END { \
	  print "quantity,value,error"; m = e / n; sd = n > 1 ? sqrt((ee - n * m * m) / (n - 1)) : ""; \
	  printf "post_peak_stress_drop,%.4g,\n", d / n; printf "failure_strain,%.4g,%s\n", m, sd; \
	  printf "broken_beams_at_end_fraction,%.4g,\n", b / n }' $< > $@

$(CC)/table.md: $(CC)/ours.csv $(CC)/peaks.csv data/reference/compression.csv
	@{ echo "# Confined compression (Kun et al. 1999 Figs. 7-9)"; echo; \
	   echo "$(CC_CELLS) cells, t_ε = 3 %, t_Θ = 4°, platens at 0.2 m/s each, seeds: $(CC_SEEDS)."; echo; \
	   awk -F, -f scripts/compare.awk data/reference/compression.csv $<; echo; \
	   echo "| seed | failure strain | peak stress (Pa) | stress drop after peak | broken beams |"; echo "|---|---|---|---|---|"; \
	   awk -F, 'NR > 1 { printf "| %s | %.4g | %.4g | %.3f | %.3f |\n", $$1, $$2, $$3, $$4, $$5 }' $(CC)/peaks.csv; } > $@

$(CC)/stress-strain.png: $(foreach s,$(CC_SEEDS),$(CC)/curve-s$(s).csv) pipelines/plots/compression.gp
	@gnuplot -e "files='$(filter %.csv,$^)'; out='$(CC)/stress-strain'" pipelines/plots/compression.gp

# Broken beams at three times (Fig. 8), first seed: only the broken beams drawn, cells by speed.
CC_S1 := $(firstword $(CC_SEEDS))
$(CC)/broken-maps: $(CC)/run-s$(CC_S1).h5
	@mkdir -p $@
	@for t in $(CC_MAP_TIMES); do $(BIN)/render $< --time $$t --beams broken --colour none --axes -q -o $@/broken-$$t.png; \
	  $(BIN)/render $< --time $$t --beams broken --colour none --axes -q -o $@/broken-$$t.svg; done
	@touch $@
