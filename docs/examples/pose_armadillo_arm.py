# Pose an arm of the armadillo: feet fixed, the right hand raised and turned (docs/python.md).
import sys, primo
mesh = primo.load_mesh(sys.argv[1] if len(sys.argv) > 1 else "../shared/meshes/armadillo_29k.obj")
c = mesh.face_centroids()
feet, hand = c[:, 1] < -0.45, (c[:, 0] > 0.3) & (c[:, 1] > 0)  # boolean masks over faces
deformer = primo.Deformer(mesh, [primo.Handle(feet), primo.Handle(hand, name="hand")])
deformer.set_handle_transform(1, translate=[-0.05, 0.2, 0.1], axis=[0, 0, 1], angle_deg=40)
report = deformer.solve()
print(report)
primo.save_mesh(mesh.with_vertices(deformer.vertices()), sys.argv[2] if len(sys.argv) > 2 else "armadillo-posed.obj")
