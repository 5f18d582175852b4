# impact: Kun et al. 1999 §3.3.2, Figs. II and 12 (physics/polygon-dem.md §8.4).
# A 0.40 m × 0.20 m block of 40 × 20 cells; the cell at the middle of the bottom layer flies into it with
# the paper's 457 J. Snapshots at 4e-4, 1.5e-3 and 3e-3 s; β of F(m) ~ m^-β by both estimators (the
# maximum-likelihood fit, and the paper's slope of the log-binned F(m) over 2 … 25 cells with its error from
# the seed-to-seed spread) at the paper's size and two larger ones; the largest fragment's share of the
# mass against the energy per mass.
#   make -f Makefile.analysis impact [IM_SEEDS='1 2 3'] [IM_LARGE_SEEDS='1 2'] [JOBS=2]
IM := $(RESULTS)/impact
# 16 seeds resolve 0.1 in β at 2σ at the paper's size (the seed-to-seed standard deviation of the
# log-binned slope is about 0.18, its jackknife error over 16 seeds 0.05). The larger sizes have four times the
# cells and twice the steps (about ten times the CPU a run); 12 seeds resolve 0.1 at 2σ there too.
IM_SEEDS ?= $(if $(MINI),1 2,$(shell seq 1 16))
IM_LARGE_SEEDS ?= $(if $(MINI),1 2,$(wordlist 1,12,$(IM_SEEDS)))
IM_S1 := $(firstword $(IM_SEEDS))
# The paper's estimator: the weighted slope of the log-binned F(m) over fragments of 2 to 25 cells, the
# decade above the single cells over which F(m) is straight (χ²/dof 1.2 at the paper's size; beyond 25 cells
# it bends).
IM_LOGBIN := --logbin-min 2cells --logbin-max 25cells
IM_FIT_OPTIONS := $(IM_LOGBIN) $(if $(MINI),--bootstrap 20 --gof-samples 20 --min-tail 5,--bootstrap 100 --gof-samples 100)
# MINI: cells of 2 cm and short runs.
IM_SHORT := $(if $(MINI),--stop.t_max 1e-3 --output.frame_interval 2e-4,)

# Sizes: name, block (m), cells, seeds, dem-run options. t_max (5 ms in the scene) scales with the block:
# the model has no length scale (unit test DemModel.ImpactOnABlockTwiceAsLargeBreaksTheSameBeams), so times
# go with lengths at a given energy per mass, and dt with the cell size.
#  paper:       the paper's block and projectile.
#  large-block: the same cells in a block twice as wide and tall, with 4 × 457 J: the same energy per mass
#               (the experiments' control parameter, cf. the largest fragment below), so only the number of
#               cells changes. By the scaling it is also finer cells in the paper's block hit by one fine
#               cell of 457 J.
#  fine-cells:  cells half as large in the paper's block, hit by the same projectile: 457 J into every cell
#               whose centroid lies in the square of the paper's cell (1 cm) at the middle of the bottom edge.
IM_SIZES := paper large-block fine-cells
IM_paper_BLOCK := 0.40x0.20
IM_paper_CELLS := $(if $(MINI),20x10,40x20)
IM_paper_SEEDS = $(IM_SEEDS)
IM_paper_RUN := $(IM_SHORT)
IM_large-block_BLOCK := 0.80x0.40
IM_large-block_CELLS := $(if $(MINI),40x20,80x40)
IM_large-block_SEEDS = $(IM_LARGE_SEEDS)
IM_large-block_RUN := --loading.impact_energy 1828 $(if $(MINI),--stop.t_max 2e-3 --output.frame_interval 4e-4,--stop.t_max 0.01)
IM_fine-cells_BLOCK := 0.40x0.20
IM_fine-cells_CELLS := $(if $(MINI),40x20,80x40)
IM_fine-cells_SEEDS = $(IM_LARGE_SEEDS)
IM_fine-cells_RUN := --loading.impact_width $(if $(MINI),0.02 --integrator.dt 1e-6,0.01 --integrator.dt 5e-7) $(IM_SHORT)

# The largest fragment against the energy per mass: the paper's block hit with 1/4 … 8 times 457 J, in steps
# of √2 up to 4 times.
IM_ENERGIES := $(if $(MINI),914 1828,114 162 228 323 646 914 1293 1828 3656)
IM_SCAN_SEEDS ?= $(if $(MINI),1 2,$(wordlist 1,4,$(IM_SEEDS)))
IM_FRAGMENTS = $(BIN)/fragment-count $< --min-cells 2 -q -o $@

.PHONY: impact
impact: $(IM)/table.md $(IM)/histogram.png $(IM)/largest.png $(IM)/snapshots
	@cat $(IM)/table.md

# mesh, run and fragments of size $(1), seed %
define IM_SIZE_RULES
$(IM)/$(1)/mesh-s%.h5: | build
	@mkdir -p $$(@D)
	$$(LAUNCH) $$(BIN)/mesh-gen voronoi --shape rect --size $(IM_$(1)_BLOCK) --cells $(IM_$(1)_CELLS) --seed $$* -q -o $$@

$(IM)/$(1)/run-s%.h5: $(IM)/$(1)/mesh-s%.h5 data/scenes/impact.ini | build
	@echo "dem-run impact $(1) seed $$*"
	$$(RUN_ENV) $$(LAUNCH) $$(BIN)/dem-run $$(THREADS_OPT) --scene data/scenes/impact.ini $$< -q -o $$@ $(IM_$(1)_RUN)

$(IM)/$(1)/frag-s%.h5: $(IM)/$(1)/run-s%.h5
	$$(IM_FRAGMENTS)

# Pooled over seeds: both estimators, the histogram, and the spread over seeds.
$(IM)/$(1)/fit.txt: $$(foreach s,$$(IM_$(1)_SEEDS),$(IM)/$(1)/frag-s$$(s).h5)
	$$(BIN)/powerlaw-fit $$^ --column mass $$(IM_FIT_OPTIONS) --format text --histogram-csv $(IM)/$(1)/histogram.csv -q -o $$@
endef
$(foreach z,$(IM_SIZES),$(eval $(call IM_SIZE_RULES,$(z))))

# Energy scan: energy/run-<J>-s<seed>.h5 on the paper-size meshes.
.SECONDEXPANSION:
$(IM)/energy/run-%.h5: $$(IM)/paper/mesh-$$(lastword $$(subst -, ,$$*)).h5 data/scenes/impact.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r energy seed <<< "$*"; echo "dem-run impact $$energy J $$seed"; \
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/impact.ini $< -q -o $@ \
	  --loading.impact_energy $$energy $(IM_SHORT)

$(IM)/energy/frag-%.h5: $(IM)/energy/run-%.h5
	$(IM_FRAGMENTS)

# One row per size: block, cells, projectile, energy per mass, seeds, then both estimators (scripts/fit-row.awk).
$(IM)/betas.csv: $(foreach z,$(IM_SIZES),$(IM)/$(z)/fit.txt) scripts/fit-row.awk
	@{ echo "size,block_m,cells,seeds,impact_energy_J,energy_per_mass_J_per_kg,$$(awk -v header=1 -f scripts/fit-row.awk < /dev/null)"; \
	  for z in $(IM_SIZES); do \
	    case $$z in paper) b=$(IM_paper_BLOCK) c=$(IM_paper_CELLS) n="$(IM_paper_SEEDS)" e=457;; \
	      large-block) b=$(IM_large-block_BLOCK) c=$(IM_large-block_CELLS) n="$(IM_large-block_SEEDS)" e=1828;; \
	      fine-cells) b=$(IM_fine-cells_BLOCK) c=$(IM_fine-cells_CELLS) n="$(IM_fine-cells_SEEDS)" e=457;; esac; \
	    m=$$(awk -v b=$$b 'BEGIN { split(b, s, "x"); print 5000 * 0.01 * s[1] * s[2] }'); \
	    printf "%s,%s,%s,%d,%s,%.4g,%s\n" $$z $$b $$c $$(wc -w <<< "$$n") $$e $$(awk -v e=$$e -v m=$$m 'BEGIN { print e / m }') \
	      "$$(awk -f scripts/fit-row.awk $(IM)/$$z/fit.txt)"; \
	  done; } > $@

# m_max / M per energy: the paper-size runs at 457 J and the scan, mean ± standard error over seeds.
IM_SCAN_FRAGS = $(foreach e,$(IM_ENERGIES),$(foreach s,$(IM_SCAN_SEEDS),$(IM)/energy/frag-$(e)-s$(s).h5))
$(IM)/largest.csv: $(IM_SCAN_FRAGS) $(foreach s,$(IM_SCAN_SEEDS),$(IM)/paper/frag-s$(s).h5) scripts/largest-share.sh
	@{ bash scripts/largest-share.sh --header; \
	  for e in $$(tr ' ' '\n' <<< "457 $(IM_ENERGIES)" | sort -n); do \
	    if [[ $$e == 457 ]]; then bash scripts/largest-share.sh $$e $(foreach s,$(IM_SCAN_SEEDS),$(IM)/paper/frag-s$(s).h5); \
	    else bash scripts/largest-share.sh $$e $(foreach s,$(IM_SCAN_SEEDS),$(IM)/energy/frag-$$e-s$(s).h5); fi; \
	  done; } > $@

# The exponent of m_max/M ~ (E/M)^-λ over the fragmented points (m_max/M < 0.5; above, the block is only
# cracked) up to the smallest m_max/M: beyond it the one-cell projectile punches through and splits the block.
# Equal weights: an error from 4 seeds is itself too uncertain to weight by.
$(IM)/largest-fit.txt: $(IM)/largest.csv scripts/loglog-fit.awk
	@awk -F, -v x=2 -v y=4 -v ymax=0.5 -v to_min=1 -f scripts/loglog-fit.awk $< > $@

$(IM)/ours.csv: $(IM)/betas.csv $(IM)/largest-fit.txt $(IM)/paper/run-s$(IM_S1).h5
	@{ echo "quantity,value,error"; \
	   awk -F, '/^#/ || NR == 1 { next } { k[$$1] = $$0 } END { \
	     split(k["paper"], p, ","); split(k["large-block"], l, ","); split(k["fine-cells"], f, ","); \
	     printf "beta_logbin,%s,%s\nbeta_mle,%s,%s\n", p[16], p[17], p[8], p[10]; \
	     printf "beta_logbin_large_block,%s,%s\nbeta_logbin_fine_cells,%s,%s\n", l[16], l[17], f[16], f[17] }' $<; \
	   awk '{ v[$$1] = $$2 } END { printf "largest_share_exponent,%s,%s\n", v["exponent"], v["exponent_stderr"] }' $(IM)/largest-fit.txt; \
	   echo "impactor_energy_J,$$($(BIN)/observables $(word 3,$^) --parameter derived.kick_kinetic_energy),"; \
	   echo "impactor_speed_m_s,$$($(BIN)/observables $(word 3,$^) --parameter derived.kick_mean_speed),"; } > $@

$(IM)/table.md: $(IM)/ours.csv $(IM)/betas.csv $(IM)/largest.csv $(IM)/largest-fit.txt data/reference/impact.csv
	@{ echo "# Projectile impact on a block (Kun et al. 1999 Figs. II, 12)"; echo; \
	   echo "t_ε = 3 %, t_Θ = 4°, single cells left out, seeds pooled. β of F(m) ~ m^-β by two estimators: the"; \
	   echo "maximum-likelihood fit (x_min by minimum KS distance, bootstrap σ, goodness-of-fit p; per seed: mean ± SE)"; \
	   echo "and the paper's, the weighted slope of the log-binned F(m) over fragments of 2 … 25 cells (bins between"; \
	   echo "the cell-count clusters), pooled ± its jackknife error over seeds (per seed: mean ± SE). The paper's"; \
	   echo "projectile: 400 m/s, ≈ 457 J; ours keeps the 457 J (the cell our mesh puts there is lighter)."; echo; \
	   awk -F, -f scripts/compare.awk data/reference/impact.csv $<; echo; \
	   echo "| size | block (m) | cells | seeds | E/M (J/kg) | fragments | β MLE ± σ_boot | x_min (cells) | n_tail | GoF p | MLE per seed | β log-binned ± jackknife | χ²/dof | log-binned per seed |"; \
	   echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"; \
	   awk -F, '/^#/ || NR == 1 { next } { for (i = 1; i <= NF; i++) if ($$i == "") $$i = "–"; \
	     printf "| %s | %s | %s | %s | %s | %s | %s ± %s | %s | %s | %s | %s ± %s | %s ± %s | %s | %s ± %s |\n", \
	       $$1, $$2, $$3, $$4, $$6, $$7, $$8, $$10, $$11, $$12, $$13, $$14, $$15, $$16, $$17, $$18, $$19, $$20 }' $(IM)/betas.csv; echo; \
	   echo "Sizes: paper = the paper's block and projectile; large-block = the same cells in a block twice as large"; \
	   echo "hit with 4 × 457 J (the same energy per mass; the model has no length scale, so this is also the paper's"; \
	   echo "block of cells half as large hit by one of them with 457 J); fine-cells = cells half as large, hit by the"; \
	   echo "same projectile (457 J into the cells in the paper cell's 1 cm square at the middle of the bottom edge)."; echo; \
	   echo "Largest fragment against the energy per mass (paper's block, projectile energy scanned, seeds $(IM_SCAN_SEEDS)):"; echo; \
	   echo "| E (J) | E/M (J/kg) | seeds | m_max/M |"; echo "|---|---|---|---|"; \
	   awk -F, '/^#/ || NR == 1 { next } { printf "| %s | %s | %s | %s ± %s |\n", $$1, $$2, $$3, $$4, $$5 }' $(IM)/largest.csv; echo; \
	   awk '{ v[$$1] = $$2 } END { printf "m_max/M ~ (E/M)^%s ± %s (least squares of the logs) over the %d points from\n", \
	     v["exponent"], v["exponent_stderr"], v["points"]; \
	     printf "E/M = %s to %s J/kg: m_max/M < 0.5, up to its minimum (at larger energies the one-cell projectile\n", v["x_min"], v["x_max"]; \
	     print "punches a channel through the block and splits it in two: m_max/M grows again)." }' $(IM)/largest-fit.txt; } > $@

# F(m) of the three sizes against the fragment size in cells (m over the mean cell mass), the paper size's
# log-binned fit over 2 … 25 cells and the paper's slope −1.98.
$(IM)/histogram.png: $(foreach z,$(IM_SIZES),$(IM)/$(z)/fit.txt) pipelines/plots/histogram.gp
	@units=$$(for z in $(IM_SIZES); do awk '$$1 == "logbin_cell_mass" { printf "%s ", $$2 }' $(IM)/$$z/fit.txt; done); \
	line=$$(awk '{ v[$$1] = $$2 } END { printf "a=%s; s=%s", v["logbin_intercept"], v["logbin_slope"] }' $<); \
	gnuplot -e "dir='$(IM)'; sizes='$(IM_SIZES)'; units='$$units'; $$line; lo=2; hi=25; beta=1.98; \
	  title='impact: F(m) pooled over seeds'; out='$(IM)/histogram'" pipelines/plots/histogram.gp

$(IM)/largest.png: $(IM)/largest.csv $(IM)/largest-fit.txt pipelines/plots/largest.gp
	@gnuplot -e "csv='$<'; fit='$(word 2,$^)'; xlabel='energy per mass E/M (J/kg)'; title='impact: largest fragment'; \
	  out='$(IM)/largest'" pipelines/plots/largest.gp

$(IM)/snapshots: $(IM)/paper/run-s$(IM_S1).h5 $(IM)/paper/frag-s$(IM_S1).h5
	@mkdir -p $@
	@for t in 4e-4 1.5e-3 3e-3; do $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $@/impact-$$t.png; \
	  $(BIN)/render $< --time $$t --colour speed --beams strain -q -o $@/impact-$$t.svg; done
	@$(BIN)/render $< --fragments $(word 2,$^) --beams off -q -o $@/fragments.png
	@touch $@
