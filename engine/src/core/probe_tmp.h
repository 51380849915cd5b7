#pragma once
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
struct ProbeAcc { std::map<std::string,double> t; ~ProbeAcc(){ for(auto&[k,v]:t) std::fprintf(stderr,"PROBE %-24s %8.1f ms\n",k.c_str(),v);} };
inline ProbeAcc g_probe;
struct Probe { const char* n; std::chrono::steady_clock::time_point s=std::chrono::steady_clock::now(); ~Probe(){ g_probe.t[n]+=std::chrono::duration<double,std::milli>(std::chrono::steady_clock::now()-s).count(); } };
