"""Small shared pieces every part uses: errors, findings, file writing, safe XML, numbers, poses, the scene
model, Gazebo's stock material colours, package lookup and the package's own data files. Nothing here imports
another part of worldgen."""
