"""plot-passes on multi-pass output folders written here (the files' documented columns):
passes.png and residual_depth.png of one run, ratchet.png of several with --compare, each run
labelled with its scene and hardening law from scene.resolved.toml."""
import os

from rollerpy.plots import passes


def write_run(folder, name, material, shear_per_pass):
    os.makedirs(folder)
    with open(os.path.join(folder, "scene.resolved.toml"), "w") as f:
        f.write('name = "%s"\n[material]\nE = 210000.0\nyield_stress = 888.0\n%s\n' % (name, material))
    with open(os.path.join(folder, "summary.json"), "w") as f:
        f.write('{"scene": "%s", "passes": {"verdict": "ratchetting", "p0_over_k": 4.5}}' % name)
    cols = ("step,pass,max_plastic_increment,mean_plastic_increment,band_plastic_increment,surface_ux,"
            "surface_uy,surface_dux,surface_duy,shear_depth,residual_shear_strain,residual_shear_increment,"
            "peak_pressure,contact_half_width,track_start,track_end")
    with open(os.path.join(folder, "passes.csv"), "w") as f:
        f.write(cols + "\n")
        for p, g in enumerate(shear_per_pass, start=1):
            f.write("%d,%d,1e-2,%g,1e-3,0,0,0,-1e-5,1.0,0,%g,2300,2.0,96,104\n" % (21 * p, p, 4e-4 / p, g))
    with open(os.path.join(folder, "residual_depth.csv"), "w") as f:
        f.write("step,pass,x,depth,sxx,syy,szz,sxy,eq_plastic_strain,back_xx,back_yy,back_zz,back_xy\n")
        for p in range(1, len(shear_per_pass) + 1):
            for depth in (0.1, 0.5, 1.0, 2.0):
                f.write("%d,%d,100,%g,%g,0,-10,5,1e-3,1,0,-1,0\n" % (21 * p, p, depth, -100 * depth))


def test_one_run_and_a_comparison_write_their_figures(tmp_path):
    epp = str(tmp_path / "epp")
    kin = str(tmp_path / "kin")
    af = str(tmp_path / "af")
    write_run(epp, "shakedown_p45", "tangent_modulus = 0.0", [3e-3, -6e-4, -8e-4])
    write_run(kin, "shakedown_kinematic_p45", 'hardening = "kinematic"\ntangent_modulus = 4200.0',
              [3e-3, -8e-4, -5e-4])
    write_run(af, "shakedown_kinematic_p45", 'hardening = "chaboche"\nchaboche_C = [4286.0]\n'
              'chaboche_gamma = [20.0]', [3e-3, -8e-4, -4e-4])
    written = passes.plot(epp)
    assert all(os.path.getsize(p) > 10000 for p in written)
    assert passes.run_label(epp) == "shakedown_p45, isotropic E_T=0"
    assert passes.run_label(kin) == "shakedown_kinematic_p45, kinematic E_T=4200"
    assert passes.run_label(af) == "shakedown_kinematic_p45, chaboche C=[4286.0] γ=[20.0]"
    # A stationary run says which load it rolled with; a transient one its backend.
    st = str(tmp_path / "st")
    write_run(st, "shakedown_p45", 'tangent_modulus = 0.0\n[passes]\nmethod = "stationary"\n'
              'stationary_contact = "roller"', [3e-3, -6e-4])
    assert passes.run_label(st) == "shakedown_p45, isotropic E_T=0, stationary, roller's contact"
    with open(os.path.join(kin, "scene.resolved.toml"), "a") as f:
        f.write('[contact]\nbackend = "penalty"\n')
    assert passes.run_label(kin) == "shakedown_kinematic_p45, kinematic E_T=4200, penalty"
    passes.main([epp, "--compare", kin, af, st])
    assert os.path.getsize(os.path.join(epp, "ratchet.png")) > 10000


def test_residual_depth_leaves_out_a_vanishing_shear_and_ends_below_what_the_passes_left():
    def rows(sxy):
        # sigma_xx and the plastic strain down to 3 mm, nothing below it, on a 16 mm deep strip
        return [{"pass": 1, "depth": d, "sxx": -100.0 if d <= 3.0 else 0.0, "szz": -50.0 if d <= 3.0 else 0.0,
                 "sxy": sxy, "eq_plastic_strain": 1e-3 if d <= 3.0 else 0.0} for d in (0.5, 1.0, 2.0, 3.0, 8.0, 16.0)]
    uniform = passes.depth_panels(rows(0.0), cap=16.0)
    assert "sxy" not in uniform.keys and "residual σ_xy [MPa]" not in uniform.labels
    assert len(uniform.keys) == len(uniform.labels) == 3 and "σ_xy = 0" in uniform.note
    assert uniform.depth == 4.5  # 1.5 x the 3 mm the passes reached, not the strip's 16 mm
    sheared = passes.depth_panels(rows(5.0), cap=16.0)
    assert "sxy" in sheared.keys and sheared.note == ""
    assert sheared.depth == 16.0  # sigma_xy reaches the bottom
    assert passes.depth_panels(rows(0.0), cap=2.0).depth == 2.0


def test_a_run_with_fatigue_draws_its_indices_and_says_its_surface_and_life(tmp_path):
    out = str(tmp_path / "fatigue")
    write_run(out, "wheel_rail_r260", "tangent_modulus = 0.0", [3e-3, 2e-3])
    with open(os.path.join(out, "fatigue.csv"), "w") as f:
        f.write("step,pass,x,depth,dang_van,dang_van_index,dang_van_shear,dang_van_hydrostatic,path_radius,"
                "shear_amplitude,max_hydrostatic,fi_sub,fi_sub_index\n")
        for p in (1, 2):
            for depth in (0.4, 1.2, 2.0, 5.0, 20.0, 80.0):
                index = 1.5 / (1.0 + depth / 2.0)
                f.write("%d,%d,100,%g,%g,%g,300,-200,250,280,-100,300,%g\n"
                        % (21 * p, p, depth, 300 * index, index, 1.1 * index))
    with open(os.path.join(out, "summary.json"), "w") as f:
        f.write('{"scene": "wheel_rail_r260", "passes": {"verdict": "ratchetting"}, "fatigue": {"pass": 2, '
                '"surface_index": 0.39, "traction_coefficient": 0.5, "shear_yield": 161.7, '
                '"peak_pressure": 1408.6, "ratchetting_life": 208.0}}')
    written = passes.plot(out)
    assert os.path.join(out, "fatigue.png") in written
    assert os.path.getsize(os.path.join(out, "fatigue.png")) > 10000
    title = passes.fatigue_title("t", {"pass": 2, "surface_index": 0.39, "traction_coefficient": 0.5,
                                       "shear_yield": 161.7, "peak_pressure": 1408.6, "ratchetting_life": None})
    assert "FI_surf 0.39" in title and "k/p0 = 0.115" in title and "no surface ratchet" in title
    # A run without [fatigue] draws no fatigue figure.
    plain = str(tmp_path / "plain")
    write_run(plain, "shakedown_p45", "tangent_modulus = 0.0", [3e-3])
    assert not any(p.endswith("fatigue.png") for p in passes.plot(plain))
