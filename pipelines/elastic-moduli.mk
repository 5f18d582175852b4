# elastic-moduli: Kun et al. 1999 §3.1, Figs. 4-6 (physics/polygon-dem.md §8.1).
# A 25 × 40 sample (0.25 m × 0.40 m) pulled and pushed by its top and bottom layers at E from 1e8 to 4e9 Pa
# (Y = 1e9 Pa fixed): the effective Young modulus K (slope of σ(ε)) and Poisson ratio ν in tension, in
# compression, and for the pure beam lattice (contacts off).
#   make -f Makefile.analysis elastic-moduli [EM_SEEDS='1 2'] [JOBS=2]
EM := $(RESULTS)/elastic-moduli
EM_E := $(if $(MINI),1e8 5e8,1e8 2e8 5e8 1e9 2e9 4e9)
EM_CELLS := $(if $(MINI),10x16,25x40)
EM_MODES := tension compression beams
EM_SEEDS ?= $(firstword $(SEEDS))
EM_CASES := $(foreach s,$(EM_SEEDS),$(foreach e,$(EM_E),$(foreach m,$(EM_MODES),$(EM)/runs/E$(e)-$(m)-s$(s))))
# Fit window: after the ramp (1 ms) and a few transit times of the sample.
EM_AFTER := 3e-3

.PHONY: elastic-moduli
elastic-moduli: $(EM)/table.md $(EM)/moduli.png $(EM)/curves.png
	@cat $(EM)/table.md

$(EM)/mesh-s%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape rect --size 0.25x0.40 --cells $(EM_CELLS) --seed $* -q -o $@

# runs/E<modulus>-<mode>-s<seed>.h5
.SECONDEXPANSION:
$(EM)/runs/E%.h5: $$(EM)/mesh-$$(lastword $$(subst -, ,$$*)).h5 data/scenes/uniaxial.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r modulus mode seed <<< "$*"; \
	case $$mode in \
	  tension) opts="--loading.direction tension" ;; \
	  compression) opts="--loading.direction compression" ;; \
	  beams) opts="--loading.direction tension --physics.contacts off --physics.damping off" ;; \
	esac; \
	echo "dem-run uniaxial E=$$modulus $$mode seed $$seed"; \
	$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/uniaxial.ini $< --material.beam_modulus $$modulus $$opts -q -o $@

# One line per run: E mode seed K K_err nu nu_err
$(EM)/runs/%.fit: $(EM)/runs/%.h5
	@IFS=- read -r modulus mode seed <<< "$*"; \
	k=$$($(BIN)/observables $< --fit stress:axial_strain --after $(EM_AFTER)); \
	n=$$($(BIN)/observables $< --fit lateral_strain:axial_strain --after $(EM_AFTER)); \
	awk -v e="$${modulus#E}" -v m="$$mode" -v s="$${seed#s}" -v k="$$k" -v n="$$n" 'BEGIN { \
	  split(k, a, "\n"); split(n, b, "\n"); for (i in a) { split(a[i], p, " "); K[p[1]] = p[2] } \
	  for (i in b) { split(b[i], p, " "); N[p[1]] = p[2] } \
	  printf "%s,%s,%s,%.6g,%.3g,%.6g,%.3g\n", e, m, s, K["slope"], K["slope_stderr"], -N["slope"], N["slope_stderr"] }' > $@

$(EM)/moduli.csv: $(addsuffix .fit,$(EM_CASES))
	@{ echo "beam_modulus_Pa,mode,seed,K_Pa,K_stderr_Pa,nu,nu_stderr"; cat $^ | sort -t, -k2,2 -k1,1g -k3,3n; } > $@

# Our numbers for the comparison with the paper's statements (data/reference/elastic-moduli.csv).
$(EM)/ours.csv: $(EM)/moduli.csv
	@awk -F, 'NR > 1 { key = $$2 "," $$1; K[key] += $$4; N[key] += $$6; c[key]++; if ($$2 == "tension") { r = $$4 / $$1; s += r; ss += r * r; m++; E[m] = $$1; KT[m] = $$4 } } \
	END { print "quantity,value,error"; \
	  kt = K["tension,5e8"] / c["tension,5e8"]; kc = K["compression,5e8"] / c["compression,5e8"]; \
	  printf "K_compression_over_K_tension_at_E5e8,%.4g,\n", kc / kt; \
	  mean = s / m; printf "K_tension_over_E_spread,%.4g,\n", sqrt(ss / m - mean * mean) / mean; \
	  sx = sy = sxx = sxy = 0; for (i = 1; i <= m; i++) { sx += E[i]; sy += KT[i]; sxx += E[i] * E[i]; sxy += E[i] * KT[i] } \
	  slope = (m * sxy - sx * sy) / (m * sxx - sx * sx); icpt = (sy - slope * sx) / m; res = 0; \
	  for (i = 1; i <= m; i++) { d = (KT[i] - slope * E[i] - icpt) / KT[i]; res += d * d } \
	  printf "K_tension_linear_fit_relative_rms_residual,%.4g,\n", sqrt(res / m); \
	  printf "K_tension_linear_fit_slope,%.4g,\n", slope; \
	  if (("compression,4e9" in N) && ("compression,1e8" in N)) \
	    printf "nu_compression_rise_at_small_E,%.4g,\n", N["compression,1e8"] / c["compression,1e8"] - N["compression,4e9"] / c["compression,4e9"]; \
	  if (("compression,4e9" in K) && ("compression,2e9" in K)) \
	    printf "K_gap_ratio_E4e9_over_E2e9,%.4g,\n", (K["compression,4e9"] / c["compression,4e9"] - K["tension,4e9"] / c["tension,4e9"]) / \
	      (K["compression,2e9"] / c["compression,2e9"] - K["tension,2e9"] / c["tension,2e9"]); \
	  printf "nu_compression_minus_nu_tension_at_E5e8,%.4g,\n", N["compression,5e8"] / c["compression,5e8"] - N["tension,5e8"] / c["tension,5e8"]; \
	  kb = 0; nb = 0; q = 0; for (key in K) if (key ~ /^beams,/) { split(key, p, ","); kb += K[key] / c[key] / p[2]; nb += N[key] / c[key]; q++ } \
	  printf "K_over_E_pure_beam,%.4g,\n", kb / q; printf "nu_pure_beam,%.4g,\n", nb / q }' $< > $@

$(EM)/table.md: $(EM)/ours.csv $(EM)/moduli.csv data/reference/elastic-moduli.csv
	@{ echo "# Elastic moduli (Kun et al. 1999 Figs. 4-6)"; echo; \
	   echo "$(EM_CELLS) cells, Y = 1e9 Pa, seeds: $(EM_SEEDS). K = slope of σ(ε), ν = −slope of ΔW/W against ΔL/L, fitted after t = $(EM_AFTER) s."; echo; \
	   awk -F, -f scripts/compare.awk data/reference/elastic-moduli.csv $<; echo; \
	   echo "| E (Pa) | mode | seed | K (Pa) | ν |"; echo "|---|---|---|---|---|"; \
	   awk -F, 'NR > 1 { printf "| %s | %s | %s | %.4g ± %.2g | %.4f ± %.4f |\n", $$1, $$2, $$3, $$4, $$5, $$6, $$7 }' $(EM)/moduli.csv; } > $@

$(EM)/moduli.png: $(EM)/moduli.csv pipelines/plots/moduli.gp
	@gnuplot -e "csv='$<'; out='$(EM)/moduli'" pipelines/plots/moduli.gp

# σ(ε) of the default material (E = 5e8 Pa) in tension and compression, first seed (Fig. 4).
EM_S1 := $(firstword $(EM_SEEDS))
$(EM)/curves.csv: $(EM)/runs/E5e8-tension-s$(EM_S1).h5 $(EM)/runs/E5e8-compression-s$(EM_S1).h5
	@{ echo "axial_strain,stress_Pa"; \
	   $(BIN)/observables $(word 2,$^) --columns axial_strain,stress | grep -v "^#" | tail -n +2 | cut -d, -f2,3 | tac; \
	   $(BIN)/observables $< --columns axial_strain,stress | grep -v "^#" | tail -n +2 | cut -d, -f2,3; } > $@

$(EM)/curves.png: $(EM)/curves.csv pipelines/plots/curves.gp
	@gnuplot -e "csv='$<'; out='$(EM)/curves'" pipelines/plots/curves.gp
