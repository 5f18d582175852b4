# demo: the meshes of the paper's experiments, made and checked (README's main-job command).
# Later the explosion experiment takes this target over.
DEMO := $(RESULTS)/demo

.PHONY: demo
demo: build
	@mkdir -p $(DEMO)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.40 --cells 1100 --seed 7 -o $(DEMO)/disc.h5
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape rect --size 0.40x0.20 --cells 40x20 --disorder 1 --seed 7 -o $(DEMO)/block.h5
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape rect --size 0.25x0.40 --cells 25x40 --seed 7 -o $(DEMO)/compression.h5
	$(LAUNCH) $(BIN)/mesh-gen triangular --nodes 400x200 --spacing 1e-3 --rows-along y --notch 0.05 -o $(DEMO)/sheet.h5
	@for f in disc block compression sheet; do $(BIN)/mesh-gen check $(DEMO)/$$f.h5; echo; done
	@echo "demo: meshes in $(DEMO)/ (open them with h5dump, h5py or ParaView; layout in docs/SCHEMA.md)"
