#!/usr/bin/env python3
# The scenes of bench/sweeps/materials.json: a 5x5 grid of UV spheres (48x24 segments), one
# dielectric material for all, a point and a directional light, a camera; one file per glTF
# material extension (plain, ior + specular, clearcoat, sheen, transmission + volume), so a
# sweep reads what each lobe costs. Usage: tools/make-material-bench-scenes.py [OUT_DIR]
# (default bench/scenes).
import json, math, struct, base64, sys, os
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'bench', 'scenes')
def sphere(r=0.4, sl=48, st=24):
    pos=[]; nrm=[]; uv=[]; idx=[]
    for i in range(st+1):
        v=i/st; th=v*math.pi
        for j in range(sl+1):
            u=j/sl; ph=u*2*math.pi
            n=(math.sin(th)*math.cos(ph), math.cos(th), math.sin(th)*math.sin(ph))
            pos.append(tuple(r*c for c in n)); nrm.append(n); uv.append((u,v))
    for i in range(st):
        for j in range(sl):
            a=i*(sl+1)+j; b=a+sl+1
            idx += [a,b,a+1, a+1,b,b+1]
    return pos,nrm,uv,idx
pos,nrm,uv,idx=sphere()
blob=b''.join(struct.pack('<3f',*p) for p in pos)+b''.join(struct.pack('<3f',*n) for n in nrm)+b''.join(struct.pack('<2f',*t) for t in uv)
o1=len(pos)*12; o2=o1+len(nrm)*12; o3=o2+len(uv)*8
blob+=b''.join(struct.pack('<I',i) for i in idx)
def make(ext, name):
    mat={"name":"m","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.3,0.1,1],"metallicFactor":0.0,"roughnessFactor":0.5}}
    used=["KHR_lights_punctual"]
    if ext:
        mat["extensions"]=ext; used+=list(ext.keys())
    nodes=[]; 
    for r in range(5):
        for c in range(5):
            nodes.append({"mesh":0,"translation":[c-2.0,2.0-r,0.0]})
    lights=[{"type":"point","intensity":30,"color":[1,1,1]},{"type":"directional","intensity":2}]
    nodes.append({"translation":[2,3,4],"extensions":{"KHR_lights_punctual":{"light":0}}})
    nodes.append({"rotation":[-0.3,0.2,0,0.93],"extensions":{"KHR_lights_punctual":{"light":1}}})
    nodes.append({"camera":0,"translation":[0,0,7.5]})
    g={"asset":{"version":"2.0"},"extensionsUsed":used,"scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],
       "nodes":nodes,"cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1,"zfar":100}}],
       "extensions":{"KHR_lights_punctual":{"lights":lights}},
       "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"material":0}]}],
       "materials":[mat],
       "buffers":[{"byteLength":len(blob),"uri":"data:application/octet-stream;base64,"+base64.b64encode(blob).decode()}],
       "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":o1},{"buffer":0,"byteOffset":o1,"byteLength":o2-o1},
                      {"buffer":0,"byteOffset":o2,"byteLength":o3-o2},{"buffer":0,"byteOffset":o3,"byteLength":len(idx)*4}],
       "accessors":[{"bufferView":0,"componentType":5126,"count":len(pos),"type":"VEC3","min":[-0.4,-0.4,-0.4],"max":[0.4,0.4,0.4]},
                    {"bufferView":1,"componentType":5126,"count":len(nrm),"type":"VEC3"},
                    {"bufferView":2,"componentType":5126,"count":len(uv),"type":"VEC2"},
                    {"bufferView":3,"componentType":5125,"count":len(idx),"type":"SCALAR"}]}
    json.dump(g, open(os.path.join(OUT, 'material-%s.gltf' % name), 'w'))
make(None,'plain')
make({"KHR_materials_ior":{"ior":1.8},"KHR_materials_specular":{"specularFactor":0.8}},'ior_specular')
make({"KHR_materials_clearcoat":{"clearcoatFactor":1.0,"clearcoatRoughnessFactor":0.2}},'clearcoat')
make({"KHR_materials_sheen":{"sheenColorFactor":[1,0.8,0.6],"sheenRoughnessFactor":0.5}},'sheen')
make({"KHR_materials_transmission":{"transmissionFactor":1.0},"KHR_materials_volume":{"thicknessFactor":0.3,"attenuationDistance":1.0,"attenuationColor":[0.9,0.6,0.3]}},'transmission')

