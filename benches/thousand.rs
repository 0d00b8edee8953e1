//! A dictionary of 1,000 UNSIGNED32 VARs (2000h..23E7h) served by offset (`#[od(compact, zerocopy)]`), for the
//! lookup-cost scenario of `node_instructions` (issue 41 item 4: the instructions per SDO request do not
//! grow with the dictionary). Generated, by a loop of
//! one `#[od(index = 0x2000 + k, access = "rw")] pub vK: u32` per k in 0..1000, nothing else.

/// 1,000 VARs; `v2` is 2002h, the entry `expedited_download` writes.
#[derive(canopen::ObjectDictionary, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]
#[od(crate = "canopen::core", compact, zerocopy)]
#[repr(C)]
pub struct Thousand {
    #[od(index = 0x2000, access = "rw")]
    pub v0: u32,
    #[od(index = 0x2001, access = "rw")]
    pub v1: u32,
    #[od(index = 0x2002, access = "rw")]
    pub v2: u32,
    #[od(index = 0x2003, access = "rw")]
    pub v3: u32,
    #[od(index = 0x2004, access = "rw")]
    pub v4: u32,
    #[od(index = 0x2005, access = "rw")]
    pub v5: u32,
    #[od(index = 0x2006, access = "rw")]
    pub v6: u32,
    #[od(index = 0x2007, access = "rw")]
    pub v7: u32,
    #[od(index = 0x2008, access = "rw")]
    pub v8: u32,
    #[od(index = 0x2009, access = "rw")]
    pub v9: u32,
    #[od(index = 0x200a, access = "rw")]
    pub v10: u32,
    #[od(index = 0x200b, access = "rw")]
    pub v11: u32,
    #[od(index = 0x200c, access = "rw")]
    pub v12: u32,
    #[od(index = 0x200d, access = "rw")]
    pub v13: u32,
    #[od(index = 0x200e, access = "rw")]
    pub v14: u32,
    #[od(index = 0x200f, access = "rw")]
    pub v15: u32,
    #[od(index = 0x2010, access = "rw")]
    pub v16: u32,
    #[od(index = 0x2011, access = "rw")]
    pub v17: u32,
    #[od(index = 0x2012, access = "rw")]
    pub v18: u32,
    #[od(index = 0x2013, access = "rw")]
    pub v19: u32,
    #[od(index = 0x2014, access = "rw")]
    pub v20: u32,
    #[od(index = 0x2015, access = "rw")]
    pub v21: u32,
    #[od(index = 0x2016, access = "rw")]
    pub v22: u32,
    #[od(index = 0x2017, access = "rw")]
    pub v23: u32,
    #[od(index = 0x2018, access = "rw")]
    pub v24: u32,
    #[od(index = 0x2019, access = "rw")]
    pub v25: u32,
    #[od(index = 0x201a, access = "rw")]
    pub v26: u32,
    #[od(index = 0x201b, access = "rw")]
    pub v27: u32,
    #[od(index = 0x201c, access = "rw")]
    pub v28: u32,
    #[od(index = 0x201d, access = "rw")]
    pub v29: u32,
    #[od(index = 0x201e, access = "rw")]
    pub v30: u32,
    #[od(index = 0x201f, access = "rw")]
    pub v31: u32,
    #[od(index = 0x2020, access = "rw")]
    pub v32: u32,
    #[od(index = 0x2021, access = "rw")]
    pub v33: u32,
    #[od(index = 0x2022, access = "rw")]
    pub v34: u32,
    #[od(index = 0x2023, access = "rw")]
    pub v35: u32,
    #[od(index = 0x2024, access = "rw")]
    pub v36: u32,
    #[od(index = 0x2025, access = "rw")]
    pub v37: u32,
    #[od(index = 0x2026, access = "rw")]
    pub v38: u32,
    #[od(index = 0x2027, access = "rw")]
    pub v39: u32,
    #[od(index = 0x2028, access = "rw")]
    pub v40: u32,
    #[od(index = 0x2029, access = "rw")]
    pub v41: u32,
    #[od(index = 0x202a, access = "rw")]
    pub v42: u32,
    #[od(index = 0x202b, access = "rw")]
    pub v43: u32,
    #[od(index = 0x202c, access = "rw")]
    pub v44: u32,
    #[od(index = 0x202d, access = "rw")]
    pub v45: u32,
    #[od(index = 0x202e, access = "rw")]
    pub v46: u32,
    #[od(index = 0x202f, access = "rw")]
    pub v47: u32,
    #[od(index = 0x2030, access = "rw")]
    pub v48: u32,
    #[od(index = 0x2031, access = "rw")]
    pub v49: u32,
    #[od(index = 0x2032, access = "rw")]
    pub v50: u32,
    #[od(index = 0x2033, access = "rw")]
    pub v51: u32,
    #[od(index = 0x2034, access = "rw")]
    pub v52: u32,
    #[od(index = 0x2035, access = "rw")]
    pub v53: u32,
    #[od(index = 0x2036, access = "rw")]
    pub v54: u32,
    #[od(index = 0x2037, access = "rw")]
    pub v55: u32,
    #[od(index = 0x2038, access = "rw")]
    pub v56: u32,
    #[od(index = 0x2039, access = "rw")]
    pub v57: u32,
    #[od(index = 0x203a, access = "rw")]
    pub v58: u32,
    #[od(index = 0x203b, access = "rw")]
    pub v59: u32,
    #[od(index = 0x203c, access = "rw")]
    pub v60: u32,
    #[od(index = 0x203d, access = "rw")]
    pub v61: u32,
    #[od(index = 0x203e, access = "rw")]
    pub v62: u32,
    #[od(index = 0x203f, access = "rw")]
    pub v63: u32,
    #[od(index = 0x2040, access = "rw")]
    pub v64: u32,
    #[od(index = 0x2041, access = "rw")]
    pub v65: u32,
    #[od(index = 0x2042, access = "rw")]
    pub v66: u32,
    #[od(index = 0x2043, access = "rw")]
    pub v67: u32,
    #[od(index = 0x2044, access = "rw")]
    pub v68: u32,
    #[od(index = 0x2045, access = "rw")]
    pub v69: u32,
    #[od(index = 0x2046, access = "rw")]
    pub v70: u32,
    #[od(index = 0x2047, access = "rw")]
    pub v71: u32,
    #[od(index = 0x2048, access = "rw")]
    pub v72: u32,
    #[od(index = 0x2049, access = "rw")]
    pub v73: u32,
    #[od(index = 0x204a, access = "rw")]
    pub v74: u32,
    #[od(index = 0x204b, access = "rw")]
    pub v75: u32,
    #[od(index = 0x204c, access = "rw")]
    pub v76: u32,
    #[od(index = 0x204d, access = "rw")]
    pub v77: u32,
    #[od(index = 0x204e, access = "rw")]
    pub v78: u32,
    #[od(index = 0x204f, access = "rw")]
    pub v79: u32,
    #[od(index = 0x2050, access = "rw")]
    pub v80: u32,
    #[od(index = 0x2051, access = "rw")]
    pub v81: u32,
    #[od(index = 0x2052, access = "rw")]
    pub v82: u32,
    #[od(index = 0x2053, access = "rw")]
    pub v83: u32,
    #[od(index = 0x2054, access = "rw")]
    pub v84: u32,
    #[od(index = 0x2055, access = "rw")]
    pub v85: u32,
    #[od(index = 0x2056, access = "rw")]
    pub v86: u32,
    #[od(index = 0x2057, access = "rw")]
    pub v87: u32,
    #[od(index = 0x2058, access = "rw")]
    pub v88: u32,
    #[od(index = 0x2059, access = "rw")]
    pub v89: u32,
    #[od(index = 0x205a, access = "rw")]
    pub v90: u32,
    #[od(index = 0x205b, access = "rw")]
    pub v91: u32,
    #[od(index = 0x205c, access = "rw")]
    pub v92: u32,
    #[od(index = 0x205d, access = "rw")]
    pub v93: u32,
    #[od(index = 0x205e, access = "rw")]
    pub v94: u32,
    #[od(index = 0x205f, access = "rw")]
    pub v95: u32,
    #[od(index = 0x2060, access = "rw")]
    pub v96: u32,
    #[od(index = 0x2061, access = "rw")]
    pub v97: u32,
    #[od(index = 0x2062, access = "rw")]
    pub v98: u32,
    #[od(index = 0x2063, access = "rw")]
    pub v99: u32,
    #[od(index = 0x2064, access = "rw")]
    pub v100: u32,
    #[od(index = 0x2065, access = "rw")]
    pub v101: u32,
    #[od(index = 0x2066, access = "rw")]
    pub v102: u32,
    #[od(index = 0x2067, access = "rw")]
    pub v103: u32,
    #[od(index = 0x2068, access = "rw")]
    pub v104: u32,
    #[od(index = 0x2069, access = "rw")]
    pub v105: u32,
    #[od(index = 0x206a, access = "rw")]
    pub v106: u32,
    #[od(index = 0x206b, access = "rw")]
    pub v107: u32,
    #[od(index = 0x206c, access = "rw")]
    pub v108: u32,
    #[od(index = 0x206d, access = "rw")]
    pub v109: u32,
    #[od(index = 0x206e, access = "rw")]
    pub v110: u32,
    #[od(index = 0x206f, access = "rw")]
    pub v111: u32,
    #[od(index = 0x2070, access = "rw")]
    pub v112: u32,
    #[od(index = 0x2071, access = "rw")]
    pub v113: u32,
    #[od(index = 0x2072, access = "rw")]
    pub v114: u32,
    #[od(index = 0x2073, access = "rw")]
    pub v115: u32,
    #[od(index = 0x2074, access = "rw")]
    pub v116: u32,
    #[od(index = 0x2075, access = "rw")]
    pub v117: u32,
    #[od(index = 0x2076, access = "rw")]
    pub v118: u32,
    #[od(index = 0x2077, access = "rw")]
    pub v119: u32,
    #[od(index = 0x2078, access = "rw")]
    pub v120: u32,
    #[od(index = 0x2079, access = "rw")]
    pub v121: u32,
    #[od(index = 0x207a, access = "rw")]
    pub v122: u32,
    #[od(index = 0x207b, access = "rw")]
    pub v123: u32,
    #[od(index = 0x207c, access = "rw")]
    pub v124: u32,
    #[od(index = 0x207d, access = "rw")]
    pub v125: u32,
    #[od(index = 0x207e, access = "rw")]
    pub v126: u32,
    #[od(index = 0x207f, access = "rw")]
    pub v127: u32,
    #[od(index = 0x2080, access = "rw")]
    pub v128: u32,
    #[od(index = 0x2081, access = "rw")]
    pub v129: u32,
    #[od(index = 0x2082, access = "rw")]
    pub v130: u32,
    #[od(index = 0x2083, access = "rw")]
    pub v131: u32,
    #[od(index = 0x2084, access = "rw")]
    pub v132: u32,
    #[od(index = 0x2085, access = "rw")]
    pub v133: u32,
    #[od(index = 0x2086, access = "rw")]
    pub v134: u32,
    #[od(index = 0x2087, access = "rw")]
    pub v135: u32,
    #[od(index = 0x2088, access = "rw")]
    pub v136: u32,
    #[od(index = 0x2089, access = "rw")]
    pub v137: u32,
    #[od(index = 0x208a, access = "rw")]
    pub v138: u32,
    #[od(index = 0x208b, access = "rw")]
    pub v139: u32,
    #[od(index = 0x208c, access = "rw")]
    pub v140: u32,
    #[od(index = 0x208d, access = "rw")]
    pub v141: u32,
    #[od(index = 0x208e, access = "rw")]
    pub v142: u32,
    #[od(index = 0x208f, access = "rw")]
    pub v143: u32,
    #[od(index = 0x2090, access = "rw")]
    pub v144: u32,
    #[od(index = 0x2091, access = "rw")]
    pub v145: u32,
    #[od(index = 0x2092, access = "rw")]
    pub v146: u32,
    #[od(index = 0x2093, access = "rw")]
    pub v147: u32,
    #[od(index = 0x2094, access = "rw")]
    pub v148: u32,
    #[od(index = 0x2095, access = "rw")]
    pub v149: u32,
    #[od(index = 0x2096, access = "rw")]
    pub v150: u32,
    #[od(index = 0x2097, access = "rw")]
    pub v151: u32,
    #[od(index = 0x2098, access = "rw")]
    pub v152: u32,
    #[od(index = 0x2099, access = "rw")]
    pub v153: u32,
    #[od(index = 0x209a, access = "rw")]
    pub v154: u32,
    #[od(index = 0x209b, access = "rw")]
    pub v155: u32,
    #[od(index = 0x209c, access = "rw")]
    pub v156: u32,
    #[od(index = 0x209d, access = "rw")]
    pub v157: u32,
    #[od(index = 0x209e, access = "rw")]
    pub v158: u32,
    #[od(index = 0x209f, access = "rw")]
    pub v159: u32,
    #[od(index = 0x20a0, access = "rw")]
    pub v160: u32,
    #[od(index = 0x20a1, access = "rw")]
    pub v161: u32,
    #[od(index = 0x20a2, access = "rw")]
    pub v162: u32,
    #[od(index = 0x20a3, access = "rw")]
    pub v163: u32,
    #[od(index = 0x20a4, access = "rw")]
    pub v164: u32,
    #[od(index = 0x20a5, access = "rw")]
    pub v165: u32,
    #[od(index = 0x20a6, access = "rw")]
    pub v166: u32,
    #[od(index = 0x20a7, access = "rw")]
    pub v167: u32,
    #[od(index = 0x20a8, access = "rw")]
    pub v168: u32,
    #[od(index = 0x20a9, access = "rw")]
    pub v169: u32,
    #[od(index = 0x20aa, access = "rw")]
    pub v170: u32,
    #[od(index = 0x20ab, access = "rw")]
    pub v171: u32,
    #[od(index = 0x20ac, access = "rw")]
    pub v172: u32,
    #[od(index = 0x20ad, access = "rw")]
    pub v173: u32,
    #[od(index = 0x20ae, access = "rw")]
    pub v174: u32,
    #[od(index = 0x20af, access = "rw")]
    pub v175: u32,
    #[od(index = 0x20b0, access = "rw")]
    pub v176: u32,
    #[od(index = 0x20b1, access = "rw")]
    pub v177: u32,
    #[od(index = 0x20b2, access = "rw")]
    pub v178: u32,
    #[od(index = 0x20b3, access = "rw")]
    pub v179: u32,
    #[od(index = 0x20b4, access = "rw")]
    pub v180: u32,
    #[od(index = 0x20b5, access = "rw")]
    pub v181: u32,
    #[od(index = 0x20b6, access = "rw")]
    pub v182: u32,
    #[od(index = 0x20b7, access = "rw")]
    pub v183: u32,
    #[od(index = 0x20b8, access = "rw")]
    pub v184: u32,
    #[od(index = 0x20b9, access = "rw")]
    pub v185: u32,
    #[od(index = 0x20ba, access = "rw")]
    pub v186: u32,
    #[od(index = 0x20bb, access = "rw")]
    pub v187: u32,
    #[od(index = 0x20bc, access = "rw")]
    pub v188: u32,
    #[od(index = 0x20bd, access = "rw")]
    pub v189: u32,
    #[od(index = 0x20be, access = "rw")]
    pub v190: u32,
    #[od(index = 0x20bf, access = "rw")]
    pub v191: u32,
    #[od(index = 0x20c0, access = "rw")]
    pub v192: u32,
    #[od(index = 0x20c1, access = "rw")]
    pub v193: u32,
    #[od(index = 0x20c2, access = "rw")]
    pub v194: u32,
    #[od(index = 0x20c3, access = "rw")]
    pub v195: u32,
    #[od(index = 0x20c4, access = "rw")]
    pub v196: u32,
    #[od(index = 0x20c5, access = "rw")]
    pub v197: u32,
    #[od(index = 0x20c6, access = "rw")]
    pub v198: u32,
    #[od(index = 0x20c7, access = "rw")]
    pub v199: u32,
    #[od(index = 0x20c8, access = "rw")]
    pub v200: u32,
    #[od(index = 0x20c9, access = "rw")]
    pub v201: u32,
    #[od(index = 0x20ca, access = "rw")]
    pub v202: u32,
    #[od(index = 0x20cb, access = "rw")]
    pub v203: u32,
    #[od(index = 0x20cc, access = "rw")]
    pub v204: u32,
    #[od(index = 0x20cd, access = "rw")]
    pub v205: u32,
    #[od(index = 0x20ce, access = "rw")]
    pub v206: u32,
    #[od(index = 0x20cf, access = "rw")]
    pub v207: u32,
    #[od(index = 0x20d0, access = "rw")]
    pub v208: u32,
    #[od(index = 0x20d1, access = "rw")]
    pub v209: u32,
    #[od(index = 0x20d2, access = "rw")]
    pub v210: u32,
    #[od(index = 0x20d3, access = "rw")]
    pub v211: u32,
    #[od(index = 0x20d4, access = "rw")]
    pub v212: u32,
    #[od(index = 0x20d5, access = "rw")]
    pub v213: u32,
    #[od(index = 0x20d6, access = "rw")]
    pub v214: u32,
    #[od(index = 0x20d7, access = "rw")]
    pub v215: u32,
    #[od(index = 0x20d8, access = "rw")]
    pub v216: u32,
    #[od(index = 0x20d9, access = "rw")]
    pub v217: u32,
    #[od(index = 0x20da, access = "rw")]
    pub v218: u32,
    #[od(index = 0x20db, access = "rw")]
    pub v219: u32,
    #[od(index = 0x20dc, access = "rw")]
    pub v220: u32,
    #[od(index = 0x20dd, access = "rw")]
    pub v221: u32,
    #[od(index = 0x20de, access = "rw")]
    pub v222: u32,
    #[od(index = 0x20df, access = "rw")]
    pub v223: u32,
    #[od(index = 0x20e0, access = "rw")]
    pub v224: u32,
    #[od(index = 0x20e1, access = "rw")]
    pub v225: u32,
    #[od(index = 0x20e2, access = "rw")]
    pub v226: u32,
    #[od(index = 0x20e3, access = "rw")]
    pub v227: u32,
    #[od(index = 0x20e4, access = "rw")]
    pub v228: u32,
    #[od(index = 0x20e5, access = "rw")]
    pub v229: u32,
    #[od(index = 0x20e6, access = "rw")]
    pub v230: u32,
    #[od(index = 0x20e7, access = "rw")]
    pub v231: u32,
    #[od(index = 0x20e8, access = "rw")]
    pub v232: u32,
    #[od(index = 0x20e9, access = "rw")]
    pub v233: u32,
    #[od(index = 0x20ea, access = "rw")]
    pub v234: u32,
    #[od(index = 0x20eb, access = "rw")]
    pub v235: u32,
    #[od(index = 0x20ec, access = "rw")]
    pub v236: u32,
    #[od(index = 0x20ed, access = "rw")]
    pub v237: u32,
    #[od(index = 0x20ee, access = "rw")]
    pub v238: u32,
    #[od(index = 0x20ef, access = "rw")]
    pub v239: u32,
    #[od(index = 0x20f0, access = "rw")]
    pub v240: u32,
    #[od(index = 0x20f1, access = "rw")]
    pub v241: u32,
    #[od(index = 0x20f2, access = "rw")]
    pub v242: u32,
    #[od(index = 0x20f3, access = "rw")]
    pub v243: u32,
    #[od(index = 0x20f4, access = "rw")]
    pub v244: u32,
    #[od(index = 0x20f5, access = "rw")]
    pub v245: u32,
    #[od(index = 0x20f6, access = "rw")]
    pub v246: u32,
    #[od(index = 0x20f7, access = "rw")]
    pub v247: u32,
    #[od(index = 0x20f8, access = "rw")]
    pub v248: u32,
    #[od(index = 0x20f9, access = "rw")]
    pub v249: u32,
    #[od(index = 0x20fa, access = "rw")]
    pub v250: u32,
    #[od(index = 0x20fb, access = "rw")]
    pub v251: u32,
    #[od(index = 0x20fc, access = "rw")]
    pub v252: u32,
    #[od(index = 0x20fd, access = "rw")]
    pub v253: u32,
    #[od(index = 0x20fe, access = "rw")]
    pub v254: u32,
    #[od(index = 0x20ff, access = "rw")]
    pub v255: u32,
    #[od(index = 0x2100, access = "rw")]
    pub v256: u32,
    #[od(index = 0x2101, access = "rw")]
    pub v257: u32,
    #[od(index = 0x2102, access = "rw")]
    pub v258: u32,
    #[od(index = 0x2103, access = "rw")]
    pub v259: u32,
    #[od(index = 0x2104, access = "rw")]
    pub v260: u32,
    #[od(index = 0x2105, access = "rw")]
    pub v261: u32,
    #[od(index = 0x2106, access = "rw")]
    pub v262: u32,
    #[od(index = 0x2107, access = "rw")]
    pub v263: u32,
    #[od(index = 0x2108, access = "rw")]
    pub v264: u32,
    #[od(index = 0x2109, access = "rw")]
    pub v265: u32,
    #[od(index = 0x210a, access = "rw")]
    pub v266: u32,
    #[od(index = 0x210b, access = "rw")]
    pub v267: u32,
    #[od(index = 0x210c, access = "rw")]
    pub v268: u32,
    #[od(index = 0x210d, access = "rw")]
    pub v269: u32,
    #[od(index = 0x210e, access = "rw")]
    pub v270: u32,
    #[od(index = 0x210f, access = "rw")]
    pub v271: u32,
    #[od(index = 0x2110, access = "rw")]
    pub v272: u32,
    #[od(index = 0x2111, access = "rw")]
    pub v273: u32,
    #[od(index = 0x2112, access = "rw")]
    pub v274: u32,
    #[od(index = 0x2113, access = "rw")]
    pub v275: u32,
    #[od(index = 0x2114, access = "rw")]
    pub v276: u32,
    #[od(index = 0x2115, access = "rw")]
    pub v277: u32,
    #[od(index = 0x2116, access = "rw")]
    pub v278: u32,
    #[od(index = 0x2117, access = "rw")]
    pub v279: u32,
    #[od(index = 0x2118, access = "rw")]
    pub v280: u32,
    #[od(index = 0x2119, access = "rw")]
    pub v281: u32,
    #[od(index = 0x211a, access = "rw")]
    pub v282: u32,
    #[od(index = 0x211b, access = "rw")]
    pub v283: u32,
    #[od(index = 0x211c, access = "rw")]
    pub v284: u32,
    #[od(index = 0x211d, access = "rw")]
    pub v285: u32,
    #[od(index = 0x211e, access = "rw")]
    pub v286: u32,
    #[od(index = 0x211f, access = "rw")]
    pub v287: u32,
    #[od(index = 0x2120, access = "rw")]
    pub v288: u32,
    #[od(index = 0x2121, access = "rw")]
    pub v289: u32,
    #[od(index = 0x2122, access = "rw")]
    pub v290: u32,
    #[od(index = 0x2123, access = "rw")]
    pub v291: u32,
    #[od(index = 0x2124, access = "rw")]
    pub v292: u32,
    #[od(index = 0x2125, access = "rw")]
    pub v293: u32,
    #[od(index = 0x2126, access = "rw")]
    pub v294: u32,
    #[od(index = 0x2127, access = "rw")]
    pub v295: u32,
    #[od(index = 0x2128, access = "rw")]
    pub v296: u32,
    #[od(index = 0x2129, access = "rw")]
    pub v297: u32,
    #[od(index = 0x212a, access = "rw")]
    pub v298: u32,
    #[od(index = 0x212b, access = "rw")]
    pub v299: u32,
    #[od(index = 0x212c, access = "rw")]
    pub v300: u32,
    #[od(index = 0x212d, access = "rw")]
    pub v301: u32,
    #[od(index = 0x212e, access = "rw")]
    pub v302: u32,
    #[od(index = 0x212f, access = "rw")]
    pub v303: u32,
    #[od(index = 0x2130, access = "rw")]
    pub v304: u32,
    #[od(index = 0x2131, access = "rw")]
    pub v305: u32,
    #[od(index = 0x2132, access = "rw")]
    pub v306: u32,
    #[od(index = 0x2133, access = "rw")]
    pub v307: u32,
    #[od(index = 0x2134, access = "rw")]
    pub v308: u32,
    #[od(index = 0x2135, access = "rw")]
    pub v309: u32,
    #[od(index = 0x2136, access = "rw")]
    pub v310: u32,
    #[od(index = 0x2137, access = "rw")]
    pub v311: u32,
    #[od(index = 0x2138, access = "rw")]
    pub v312: u32,
    #[od(index = 0x2139, access = "rw")]
    pub v313: u32,
    #[od(index = 0x213a, access = "rw")]
    pub v314: u32,
    #[od(index = 0x213b, access = "rw")]
    pub v315: u32,
    #[od(index = 0x213c, access = "rw")]
    pub v316: u32,
    #[od(index = 0x213d, access = "rw")]
    pub v317: u32,
    #[od(index = 0x213e, access = "rw")]
    pub v318: u32,
    #[od(index = 0x213f, access = "rw")]
    pub v319: u32,
    #[od(index = 0x2140, access = "rw")]
    pub v320: u32,
    #[od(index = 0x2141, access = "rw")]
    pub v321: u32,
    #[od(index = 0x2142, access = "rw")]
    pub v322: u32,
    #[od(index = 0x2143, access = "rw")]
    pub v323: u32,
    #[od(index = 0x2144, access = "rw")]
    pub v324: u32,
    #[od(index = 0x2145, access = "rw")]
    pub v325: u32,
    #[od(index = 0x2146, access = "rw")]
    pub v326: u32,
    #[od(index = 0x2147, access = "rw")]
    pub v327: u32,
    #[od(index = 0x2148, access = "rw")]
    pub v328: u32,
    #[od(index = 0x2149, access = "rw")]
    pub v329: u32,
    #[od(index = 0x214a, access = "rw")]
    pub v330: u32,
    #[od(index = 0x214b, access = "rw")]
    pub v331: u32,
    #[od(index = 0x214c, access = "rw")]
    pub v332: u32,
    #[od(index = 0x214d, access = "rw")]
    pub v333: u32,
    #[od(index = 0x214e, access = "rw")]
    pub v334: u32,
    #[od(index = 0x214f, access = "rw")]
    pub v335: u32,
    #[od(index = 0x2150, access = "rw")]
    pub v336: u32,
    #[od(index = 0x2151, access = "rw")]
    pub v337: u32,
    #[od(index = 0x2152, access = "rw")]
    pub v338: u32,
    #[od(index = 0x2153, access = "rw")]
    pub v339: u32,
    #[od(index = 0x2154, access = "rw")]
    pub v340: u32,
    #[od(index = 0x2155, access = "rw")]
    pub v341: u32,
    #[od(index = 0x2156, access = "rw")]
    pub v342: u32,
    #[od(index = 0x2157, access = "rw")]
    pub v343: u32,
    #[od(index = 0x2158, access = "rw")]
    pub v344: u32,
    #[od(index = 0x2159, access = "rw")]
    pub v345: u32,
    #[od(index = 0x215a, access = "rw")]
    pub v346: u32,
    #[od(index = 0x215b, access = "rw")]
    pub v347: u32,
    #[od(index = 0x215c, access = "rw")]
    pub v348: u32,
    #[od(index = 0x215d, access = "rw")]
    pub v349: u32,
    #[od(index = 0x215e, access = "rw")]
    pub v350: u32,
    #[od(index = 0x215f, access = "rw")]
    pub v351: u32,
    #[od(index = 0x2160, access = "rw")]
    pub v352: u32,
    #[od(index = 0x2161, access = "rw")]
    pub v353: u32,
    #[od(index = 0x2162, access = "rw")]
    pub v354: u32,
    #[od(index = 0x2163, access = "rw")]
    pub v355: u32,
    #[od(index = 0x2164, access = "rw")]
    pub v356: u32,
    #[od(index = 0x2165, access = "rw")]
    pub v357: u32,
    #[od(index = 0x2166, access = "rw")]
    pub v358: u32,
    #[od(index = 0x2167, access = "rw")]
    pub v359: u32,
    #[od(index = 0x2168, access = "rw")]
    pub v360: u32,
    #[od(index = 0x2169, access = "rw")]
    pub v361: u32,
    #[od(index = 0x216a, access = "rw")]
    pub v362: u32,
    #[od(index = 0x216b, access = "rw")]
    pub v363: u32,
    #[od(index = 0x216c, access = "rw")]
    pub v364: u32,
    #[od(index = 0x216d, access = "rw")]
    pub v365: u32,
    #[od(index = 0x216e, access = "rw")]
    pub v366: u32,
    #[od(index = 0x216f, access = "rw")]
    pub v367: u32,
    #[od(index = 0x2170, access = "rw")]
    pub v368: u32,
    #[od(index = 0x2171, access = "rw")]
    pub v369: u32,
    #[od(index = 0x2172, access = "rw")]
    pub v370: u32,
    #[od(index = 0x2173, access = "rw")]
    pub v371: u32,
    #[od(index = 0x2174, access = "rw")]
    pub v372: u32,
    #[od(index = 0x2175, access = "rw")]
    pub v373: u32,
    #[od(index = 0x2176, access = "rw")]
    pub v374: u32,
    #[od(index = 0x2177, access = "rw")]
    pub v375: u32,
    #[od(index = 0x2178, access = "rw")]
    pub v376: u32,
    #[od(index = 0x2179, access = "rw")]
    pub v377: u32,
    #[od(index = 0x217a, access = "rw")]
    pub v378: u32,
    #[od(index = 0x217b, access = "rw")]
    pub v379: u32,
    #[od(index = 0x217c, access = "rw")]
    pub v380: u32,
    #[od(index = 0x217d, access = "rw")]
    pub v381: u32,
    #[od(index = 0x217e, access = "rw")]
    pub v382: u32,
    #[od(index = 0x217f, access = "rw")]
    pub v383: u32,
    #[od(index = 0x2180, access = "rw")]
    pub v384: u32,
    #[od(index = 0x2181, access = "rw")]
    pub v385: u32,
    #[od(index = 0x2182, access = "rw")]
    pub v386: u32,
    #[od(index = 0x2183, access = "rw")]
    pub v387: u32,
    #[od(index = 0x2184, access = "rw")]
    pub v388: u32,
    #[od(index = 0x2185, access = "rw")]
    pub v389: u32,
    #[od(index = 0x2186, access = "rw")]
    pub v390: u32,
    #[od(index = 0x2187, access = "rw")]
    pub v391: u32,
    #[od(index = 0x2188, access = "rw")]
    pub v392: u32,
    #[od(index = 0x2189, access = "rw")]
    pub v393: u32,
    #[od(index = 0x218a, access = "rw")]
    pub v394: u32,
    #[od(index = 0x218b, access = "rw")]
    pub v395: u32,
    #[od(index = 0x218c, access = "rw")]
    pub v396: u32,
    #[od(index = 0x218d, access = "rw")]
    pub v397: u32,
    #[od(index = 0x218e, access = "rw")]
    pub v398: u32,
    #[od(index = 0x218f, access = "rw")]
    pub v399: u32,
    #[od(index = 0x2190, access = "rw")]
    pub v400: u32,
    #[od(index = 0x2191, access = "rw")]
    pub v401: u32,
    #[od(index = 0x2192, access = "rw")]
    pub v402: u32,
    #[od(index = 0x2193, access = "rw")]
    pub v403: u32,
    #[od(index = 0x2194, access = "rw")]
    pub v404: u32,
    #[od(index = 0x2195, access = "rw")]
    pub v405: u32,
    #[od(index = 0x2196, access = "rw")]
    pub v406: u32,
    #[od(index = 0x2197, access = "rw")]
    pub v407: u32,
    #[od(index = 0x2198, access = "rw")]
    pub v408: u32,
    #[od(index = 0x2199, access = "rw")]
    pub v409: u32,
    #[od(index = 0x219a, access = "rw")]
    pub v410: u32,
    #[od(index = 0x219b, access = "rw")]
    pub v411: u32,
    #[od(index = 0x219c, access = "rw")]
    pub v412: u32,
    #[od(index = 0x219d, access = "rw")]
    pub v413: u32,
    #[od(index = 0x219e, access = "rw")]
    pub v414: u32,
    #[od(index = 0x219f, access = "rw")]
    pub v415: u32,
    #[od(index = 0x21a0, access = "rw")]
    pub v416: u32,
    #[od(index = 0x21a1, access = "rw")]
    pub v417: u32,
    #[od(index = 0x21a2, access = "rw")]
    pub v418: u32,
    #[od(index = 0x21a3, access = "rw")]
    pub v419: u32,
    #[od(index = 0x21a4, access = "rw")]
    pub v420: u32,
    #[od(index = 0x21a5, access = "rw")]
    pub v421: u32,
    #[od(index = 0x21a6, access = "rw")]
    pub v422: u32,
    #[od(index = 0x21a7, access = "rw")]
    pub v423: u32,
    #[od(index = 0x21a8, access = "rw")]
    pub v424: u32,
    #[od(index = 0x21a9, access = "rw")]
    pub v425: u32,
    #[od(index = 0x21aa, access = "rw")]
    pub v426: u32,
    #[od(index = 0x21ab, access = "rw")]
    pub v427: u32,
    #[od(index = 0x21ac, access = "rw")]
    pub v428: u32,
    #[od(index = 0x21ad, access = "rw")]
    pub v429: u32,
    #[od(index = 0x21ae, access = "rw")]
    pub v430: u32,
    #[od(index = 0x21af, access = "rw")]
    pub v431: u32,
    #[od(index = 0x21b0, access = "rw")]
    pub v432: u32,
    #[od(index = 0x21b1, access = "rw")]
    pub v433: u32,
    #[od(index = 0x21b2, access = "rw")]
    pub v434: u32,
    #[od(index = 0x21b3, access = "rw")]
    pub v435: u32,
    #[od(index = 0x21b4, access = "rw")]
    pub v436: u32,
    #[od(index = 0x21b5, access = "rw")]
    pub v437: u32,
    #[od(index = 0x21b6, access = "rw")]
    pub v438: u32,
    #[od(index = 0x21b7, access = "rw")]
    pub v439: u32,
    #[od(index = 0x21b8, access = "rw")]
    pub v440: u32,
    #[od(index = 0x21b9, access = "rw")]
    pub v441: u32,
    #[od(index = 0x21ba, access = "rw")]
    pub v442: u32,
    #[od(index = 0x21bb, access = "rw")]
    pub v443: u32,
    #[od(index = 0x21bc, access = "rw")]
    pub v444: u32,
    #[od(index = 0x21bd, access = "rw")]
    pub v445: u32,
    #[od(index = 0x21be, access = "rw")]
    pub v446: u32,
    #[od(index = 0x21bf, access = "rw")]
    pub v447: u32,
    #[od(index = 0x21c0, access = "rw")]
    pub v448: u32,
    #[od(index = 0x21c1, access = "rw")]
    pub v449: u32,
    #[od(index = 0x21c2, access = "rw")]
    pub v450: u32,
    #[od(index = 0x21c3, access = "rw")]
    pub v451: u32,
    #[od(index = 0x21c4, access = "rw")]
    pub v452: u32,
    #[od(index = 0x21c5, access = "rw")]
    pub v453: u32,
    #[od(index = 0x21c6, access = "rw")]
    pub v454: u32,
    #[od(index = 0x21c7, access = "rw")]
    pub v455: u32,
    #[od(index = 0x21c8, access = "rw")]
    pub v456: u32,
    #[od(index = 0x21c9, access = "rw")]
    pub v457: u32,
    #[od(index = 0x21ca, access = "rw")]
    pub v458: u32,
    #[od(index = 0x21cb, access = "rw")]
    pub v459: u32,
    #[od(index = 0x21cc, access = "rw")]
    pub v460: u32,
    #[od(index = 0x21cd, access = "rw")]
    pub v461: u32,
    #[od(index = 0x21ce, access = "rw")]
    pub v462: u32,
    #[od(index = 0x21cf, access = "rw")]
    pub v463: u32,
    #[od(index = 0x21d0, access = "rw")]
    pub v464: u32,
    #[od(index = 0x21d1, access = "rw")]
    pub v465: u32,
    #[od(index = 0x21d2, access = "rw")]
    pub v466: u32,
    #[od(index = 0x21d3, access = "rw")]
    pub v467: u32,
    #[od(index = 0x21d4, access = "rw")]
    pub v468: u32,
    #[od(index = 0x21d5, access = "rw")]
    pub v469: u32,
    #[od(index = 0x21d6, access = "rw")]
    pub v470: u32,
    #[od(index = 0x21d7, access = "rw")]
    pub v471: u32,
    #[od(index = 0x21d8, access = "rw")]
    pub v472: u32,
    #[od(index = 0x21d9, access = "rw")]
    pub v473: u32,
    #[od(index = 0x21da, access = "rw")]
    pub v474: u32,
    #[od(index = 0x21db, access = "rw")]
    pub v475: u32,
    #[od(index = 0x21dc, access = "rw")]
    pub v476: u32,
    #[od(index = 0x21dd, access = "rw")]
    pub v477: u32,
    #[od(index = 0x21de, access = "rw")]
    pub v478: u32,
    #[od(index = 0x21df, access = "rw")]
    pub v479: u32,
    #[od(index = 0x21e0, access = "rw")]
    pub v480: u32,
    #[od(index = 0x21e1, access = "rw")]
    pub v481: u32,
    #[od(index = 0x21e2, access = "rw")]
    pub v482: u32,
    #[od(index = 0x21e3, access = "rw")]
    pub v483: u32,
    #[od(index = 0x21e4, access = "rw")]
    pub v484: u32,
    #[od(index = 0x21e5, access = "rw")]
    pub v485: u32,
    #[od(index = 0x21e6, access = "rw")]
    pub v486: u32,
    #[od(index = 0x21e7, access = "rw")]
    pub v487: u32,
    #[od(index = 0x21e8, access = "rw")]
    pub v488: u32,
    #[od(index = 0x21e9, access = "rw")]
    pub v489: u32,
    #[od(index = 0x21ea, access = "rw")]
    pub v490: u32,
    #[od(index = 0x21eb, access = "rw")]
    pub v491: u32,
    #[od(index = 0x21ec, access = "rw")]
    pub v492: u32,
    #[od(index = 0x21ed, access = "rw")]
    pub v493: u32,
    #[od(index = 0x21ee, access = "rw")]
    pub v494: u32,
    #[od(index = 0x21ef, access = "rw")]
    pub v495: u32,
    #[od(index = 0x21f0, access = "rw")]
    pub v496: u32,
    #[od(index = 0x21f1, access = "rw")]
    pub v497: u32,
    #[od(index = 0x21f2, access = "rw")]
    pub v498: u32,
    #[od(index = 0x21f3, access = "rw")]
    pub v499: u32,
    #[od(index = 0x21f4, access = "rw")]
    pub v500: u32,
    #[od(index = 0x21f5, access = "rw")]
    pub v501: u32,
    #[od(index = 0x21f6, access = "rw")]
    pub v502: u32,
    #[od(index = 0x21f7, access = "rw")]
    pub v503: u32,
    #[od(index = 0x21f8, access = "rw")]
    pub v504: u32,
    #[od(index = 0x21f9, access = "rw")]
    pub v505: u32,
    #[od(index = 0x21fa, access = "rw")]
    pub v506: u32,
    #[od(index = 0x21fb, access = "rw")]
    pub v507: u32,
    #[od(index = 0x21fc, access = "rw")]
    pub v508: u32,
    #[od(index = 0x21fd, access = "rw")]
    pub v509: u32,
    #[od(index = 0x21fe, access = "rw")]
    pub v510: u32,
    #[od(index = 0x21ff, access = "rw")]
    pub v511: u32,
    #[od(index = 0x2200, access = "rw")]
    pub v512: u32,
    #[od(index = 0x2201, access = "rw")]
    pub v513: u32,
    #[od(index = 0x2202, access = "rw")]
    pub v514: u32,
    #[od(index = 0x2203, access = "rw")]
    pub v515: u32,
    #[od(index = 0x2204, access = "rw")]
    pub v516: u32,
    #[od(index = 0x2205, access = "rw")]
    pub v517: u32,
    #[od(index = 0x2206, access = "rw")]
    pub v518: u32,
    #[od(index = 0x2207, access = "rw")]
    pub v519: u32,
    #[od(index = 0x2208, access = "rw")]
    pub v520: u32,
    #[od(index = 0x2209, access = "rw")]
    pub v521: u32,
    #[od(index = 0x220a, access = "rw")]
    pub v522: u32,
    #[od(index = 0x220b, access = "rw")]
    pub v523: u32,
    #[od(index = 0x220c, access = "rw")]
    pub v524: u32,
    #[od(index = 0x220d, access = "rw")]
    pub v525: u32,
    #[od(index = 0x220e, access = "rw")]
    pub v526: u32,
    #[od(index = 0x220f, access = "rw")]
    pub v527: u32,
    #[od(index = 0x2210, access = "rw")]
    pub v528: u32,
    #[od(index = 0x2211, access = "rw")]
    pub v529: u32,
    #[od(index = 0x2212, access = "rw")]
    pub v530: u32,
    #[od(index = 0x2213, access = "rw")]
    pub v531: u32,
    #[od(index = 0x2214, access = "rw")]
    pub v532: u32,
    #[od(index = 0x2215, access = "rw")]
    pub v533: u32,
    #[od(index = 0x2216, access = "rw")]
    pub v534: u32,
    #[od(index = 0x2217, access = "rw")]
    pub v535: u32,
    #[od(index = 0x2218, access = "rw")]
    pub v536: u32,
    #[od(index = 0x2219, access = "rw")]
    pub v537: u32,
    #[od(index = 0x221a, access = "rw")]
    pub v538: u32,
    #[od(index = 0x221b, access = "rw")]
    pub v539: u32,
    #[od(index = 0x221c, access = "rw")]
    pub v540: u32,
    #[od(index = 0x221d, access = "rw")]
    pub v541: u32,
    #[od(index = 0x221e, access = "rw")]
    pub v542: u32,
    #[od(index = 0x221f, access = "rw")]
    pub v543: u32,
    #[od(index = 0x2220, access = "rw")]
    pub v544: u32,
    #[od(index = 0x2221, access = "rw")]
    pub v545: u32,
    #[od(index = 0x2222, access = "rw")]
    pub v546: u32,
    #[od(index = 0x2223, access = "rw")]
    pub v547: u32,
    #[od(index = 0x2224, access = "rw")]
    pub v548: u32,
    #[od(index = 0x2225, access = "rw")]
    pub v549: u32,
    #[od(index = 0x2226, access = "rw")]
    pub v550: u32,
    #[od(index = 0x2227, access = "rw")]
    pub v551: u32,
    #[od(index = 0x2228, access = "rw")]
    pub v552: u32,
    #[od(index = 0x2229, access = "rw")]
    pub v553: u32,
    #[od(index = 0x222a, access = "rw")]
    pub v554: u32,
    #[od(index = 0x222b, access = "rw")]
    pub v555: u32,
    #[od(index = 0x222c, access = "rw")]
    pub v556: u32,
    #[od(index = 0x222d, access = "rw")]
    pub v557: u32,
    #[od(index = 0x222e, access = "rw")]
    pub v558: u32,
    #[od(index = 0x222f, access = "rw")]
    pub v559: u32,
    #[od(index = 0x2230, access = "rw")]
    pub v560: u32,
    #[od(index = 0x2231, access = "rw")]
    pub v561: u32,
    #[od(index = 0x2232, access = "rw")]
    pub v562: u32,
    #[od(index = 0x2233, access = "rw")]
    pub v563: u32,
    #[od(index = 0x2234, access = "rw")]
    pub v564: u32,
    #[od(index = 0x2235, access = "rw")]
    pub v565: u32,
    #[od(index = 0x2236, access = "rw")]
    pub v566: u32,
    #[od(index = 0x2237, access = "rw")]
    pub v567: u32,
    #[od(index = 0x2238, access = "rw")]
    pub v568: u32,
    #[od(index = 0x2239, access = "rw")]
    pub v569: u32,
    #[od(index = 0x223a, access = "rw")]
    pub v570: u32,
    #[od(index = 0x223b, access = "rw")]
    pub v571: u32,
    #[od(index = 0x223c, access = "rw")]
    pub v572: u32,
    #[od(index = 0x223d, access = "rw")]
    pub v573: u32,
    #[od(index = 0x223e, access = "rw")]
    pub v574: u32,
    #[od(index = 0x223f, access = "rw")]
    pub v575: u32,
    #[od(index = 0x2240, access = "rw")]
    pub v576: u32,
    #[od(index = 0x2241, access = "rw")]
    pub v577: u32,
    #[od(index = 0x2242, access = "rw")]
    pub v578: u32,
    #[od(index = 0x2243, access = "rw")]
    pub v579: u32,
    #[od(index = 0x2244, access = "rw")]
    pub v580: u32,
    #[od(index = 0x2245, access = "rw")]
    pub v581: u32,
    #[od(index = 0x2246, access = "rw")]
    pub v582: u32,
    #[od(index = 0x2247, access = "rw")]
    pub v583: u32,
    #[od(index = 0x2248, access = "rw")]
    pub v584: u32,
    #[od(index = 0x2249, access = "rw")]
    pub v585: u32,
    #[od(index = 0x224a, access = "rw")]
    pub v586: u32,
    #[od(index = 0x224b, access = "rw")]
    pub v587: u32,
    #[od(index = 0x224c, access = "rw")]
    pub v588: u32,
    #[od(index = 0x224d, access = "rw")]
    pub v589: u32,
    #[od(index = 0x224e, access = "rw")]
    pub v590: u32,
    #[od(index = 0x224f, access = "rw")]
    pub v591: u32,
    #[od(index = 0x2250, access = "rw")]
    pub v592: u32,
    #[od(index = 0x2251, access = "rw")]
    pub v593: u32,
    #[od(index = 0x2252, access = "rw")]
    pub v594: u32,
    #[od(index = 0x2253, access = "rw")]
    pub v595: u32,
    #[od(index = 0x2254, access = "rw")]
    pub v596: u32,
    #[od(index = 0x2255, access = "rw")]
    pub v597: u32,
    #[od(index = 0x2256, access = "rw")]
    pub v598: u32,
    #[od(index = 0x2257, access = "rw")]
    pub v599: u32,
    #[od(index = 0x2258, access = "rw")]
    pub v600: u32,
    #[od(index = 0x2259, access = "rw")]
    pub v601: u32,
    #[od(index = 0x225a, access = "rw")]
    pub v602: u32,
    #[od(index = 0x225b, access = "rw")]
    pub v603: u32,
    #[od(index = 0x225c, access = "rw")]
    pub v604: u32,
    #[od(index = 0x225d, access = "rw")]
    pub v605: u32,
    #[od(index = 0x225e, access = "rw")]
    pub v606: u32,
    #[od(index = 0x225f, access = "rw")]
    pub v607: u32,
    #[od(index = 0x2260, access = "rw")]
    pub v608: u32,
    #[od(index = 0x2261, access = "rw")]
    pub v609: u32,
    #[od(index = 0x2262, access = "rw")]
    pub v610: u32,
    #[od(index = 0x2263, access = "rw")]
    pub v611: u32,
    #[od(index = 0x2264, access = "rw")]
    pub v612: u32,
    #[od(index = 0x2265, access = "rw")]
    pub v613: u32,
    #[od(index = 0x2266, access = "rw")]
    pub v614: u32,
    #[od(index = 0x2267, access = "rw")]
    pub v615: u32,
    #[od(index = 0x2268, access = "rw")]
    pub v616: u32,
    #[od(index = 0x2269, access = "rw")]
    pub v617: u32,
    #[od(index = 0x226a, access = "rw")]
    pub v618: u32,
    #[od(index = 0x226b, access = "rw")]
    pub v619: u32,
    #[od(index = 0x226c, access = "rw")]
    pub v620: u32,
    #[od(index = 0x226d, access = "rw")]
    pub v621: u32,
    #[od(index = 0x226e, access = "rw")]
    pub v622: u32,
    #[od(index = 0x226f, access = "rw")]
    pub v623: u32,
    #[od(index = 0x2270, access = "rw")]
    pub v624: u32,
    #[od(index = 0x2271, access = "rw")]
    pub v625: u32,
    #[od(index = 0x2272, access = "rw")]
    pub v626: u32,
    #[od(index = 0x2273, access = "rw")]
    pub v627: u32,
    #[od(index = 0x2274, access = "rw")]
    pub v628: u32,
    #[od(index = 0x2275, access = "rw")]
    pub v629: u32,
    #[od(index = 0x2276, access = "rw")]
    pub v630: u32,
    #[od(index = 0x2277, access = "rw")]
    pub v631: u32,
    #[od(index = 0x2278, access = "rw")]
    pub v632: u32,
    #[od(index = 0x2279, access = "rw")]
    pub v633: u32,
    #[od(index = 0x227a, access = "rw")]
    pub v634: u32,
    #[od(index = 0x227b, access = "rw")]
    pub v635: u32,
    #[od(index = 0x227c, access = "rw")]
    pub v636: u32,
    #[od(index = 0x227d, access = "rw")]
    pub v637: u32,
    #[od(index = 0x227e, access = "rw")]
    pub v638: u32,
    #[od(index = 0x227f, access = "rw")]
    pub v639: u32,
    #[od(index = 0x2280, access = "rw")]
    pub v640: u32,
    #[od(index = 0x2281, access = "rw")]
    pub v641: u32,
    #[od(index = 0x2282, access = "rw")]
    pub v642: u32,
    #[od(index = 0x2283, access = "rw")]
    pub v643: u32,
    #[od(index = 0x2284, access = "rw")]
    pub v644: u32,
    #[od(index = 0x2285, access = "rw")]
    pub v645: u32,
    #[od(index = 0x2286, access = "rw")]
    pub v646: u32,
    #[od(index = 0x2287, access = "rw")]
    pub v647: u32,
    #[od(index = 0x2288, access = "rw")]
    pub v648: u32,
    #[od(index = 0x2289, access = "rw")]
    pub v649: u32,
    #[od(index = 0x228a, access = "rw")]
    pub v650: u32,
    #[od(index = 0x228b, access = "rw")]
    pub v651: u32,
    #[od(index = 0x228c, access = "rw")]
    pub v652: u32,
    #[od(index = 0x228d, access = "rw")]
    pub v653: u32,
    #[od(index = 0x228e, access = "rw")]
    pub v654: u32,
    #[od(index = 0x228f, access = "rw")]
    pub v655: u32,
    #[od(index = 0x2290, access = "rw")]
    pub v656: u32,
    #[od(index = 0x2291, access = "rw")]
    pub v657: u32,
    #[od(index = 0x2292, access = "rw")]
    pub v658: u32,
    #[od(index = 0x2293, access = "rw")]
    pub v659: u32,
    #[od(index = 0x2294, access = "rw")]
    pub v660: u32,
    #[od(index = 0x2295, access = "rw")]
    pub v661: u32,
    #[od(index = 0x2296, access = "rw")]
    pub v662: u32,
    #[od(index = 0x2297, access = "rw")]
    pub v663: u32,
    #[od(index = 0x2298, access = "rw")]
    pub v664: u32,
    #[od(index = 0x2299, access = "rw")]
    pub v665: u32,
    #[od(index = 0x229a, access = "rw")]
    pub v666: u32,
    #[od(index = 0x229b, access = "rw")]
    pub v667: u32,
    #[od(index = 0x229c, access = "rw")]
    pub v668: u32,
    #[od(index = 0x229d, access = "rw")]
    pub v669: u32,
    #[od(index = 0x229e, access = "rw")]
    pub v670: u32,
    #[od(index = 0x229f, access = "rw")]
    pub v671: u32,
    #[od(index = 0x22a0, access = "rw")]
    pub v672: u32,
    #[od(index = 0x22a1, access = "rw")]
    pub v673: u32,
    #[od(index = 0x22a2, access = "rw")]
    pub v674: u32,
    #[od(index = 0x22a3, access = "rw")]
    pub v675: u32,
    #[od(index = 0x22a4, access = "rw")]
    pub v676: u32,
    #[od(index = 0x22a5, access = "rw")]
    pub v677: u32,
    #[od(index = 0x22a6, access = "rw")]
    pub v678: u32,
    #[od(index = 0x22a7, access = "rw")]
    pub v679: u32,
    #[od(index = 0x22a8, access = "rw")]
    pub v680: u32,
    #[od(index = 0x22a9, access = "rw")]
    pub v681: u32,
    #[od(index = 0x22aa, access = "rw")]
    pub v682: u32,
    #[od(index = 0x22ab, access = "rw")]
    pub v683: u32,
    #[od(index = 0x22ac, access = "rw")]
    pub v684: u32,
    #[od(index = 0x22ad, access = "rw")]
    pub v685: u32,
    #[od(index = 0x22ae, access = "rw")]
    pub v686: u32,
    #[od(index = 0x22af, access = "rw")]
    pub v687: u32,
    #[od(index = 0x22b0, access = "rw")]
    pub v688: u32,
    #[od(index = 0x22b1, access = "rw")]
    pub v689: u32,
    #[od(index = 0x22b2, access = "rw")]
    pub v690: u32,
    #[od(index = 0x22b3, access = "rw")]
    pub v691: u32,
    #[od(index = 0x22b4, access = "rw")]
    pub v692: u32,
    #[od(index = 0x22b5, access = "rw")]
    pub v693: u32,
    #[od(index = 0x22b6, access = "rw")]
    pub v694: u32,
    #[od(index = 0x22b7, access = "rw")]
    pub v695: u32,
    #[od(index = 0x22b8, access = "rw")]
    pub v696: u32,
    #[od(index = 0x22b9, access = "rw")]
    pub v697: u32,
    #[od(index = 0x22ba, access = "rw")]
    pub v698: u32,
    #[od(index = 0x22bb, access = "rw")]
    pub v699: u32,
    #[od(index = 0x22bc, access = "rw")]
    pub v700: u32,
    #[od(index = 0x22bd, access = "rw")]
    pub v701: u32,
    #[od(index = 0x22be, access = "rw")]
    pub v702: u32,
    #[od(index = 0x22bf, access = "rw")]
    pub v703: u32,
    #[od(index = 0x22c0, access = "rw")]
    pub v704: u32,
    #[od(index = 0x22c1, access = "rw")]
    pub v705: u32,
    #[od(index = 0x22c2, access = "rw")]
    pub v706: u32,
    #[od(index = 0x22c3, access = "rw")]
    pub v707: u32,
    #[od(index = 0x22c4, access = "rw")]
    pub v708: u32,
    #[od(index = 0x22c5, access = "rw")]
    pub v709: u32,
    #[od(index = 0x22c6, access = "rw")]
    pub v710: u32,
    #[od(index = 0x22c7, access = "rw")]
    pub v711: u32,
    #[od(index = 0x22c8, access = "rw")]
    pub v712: u32,
    #[od(index = 0x22c9, access = "rw")]
    pub v713: u32,
    #[od(index = 0x22ca, access = "rw")]
    pub v714: u32,
    #[od(index = 0x22cb, access = "rw")]
    pub v715: u32,
    #[od(index = 0x22cc, access = "rw")]
    pub v716: u32,
    #[od(index = 0x22cd, access = "rw")]
    pub v717: u32,
    #[od(index = 0x22ce, access = "rw")]
    pub v718: u32,
    #[od(index = 0x22cf, access = "rw")]
    pub v719: u32,
    #[od(index = 0x22d0, access = "rw")]
    pub v720: u32,
    #[od(index = 0x22d1, access = "rw")]
    pub v721: u32,
    #[od(index = 0x22d2, access = "rw")]
    pub v722: u32,
    #[od(index = 0x22d3, access = "rw")]
    pub v723: u32,
    #[od(index = 0x22d4, access = "rw")]
    pub v724: u32,
    #[od(index = 0x22d5, access = "rw")]
    pub v725: u32,
    #[od(index = 0x22d6, access = "rw")]
    pub v726: u32,
    #[od(index = 0x22d7, access = "rw")]
    pub v727: u32,
    #[od(index = 0x22d8, access = "rw")]
    pub v728: u32,
    #[od(index = 0x22d9, access = "rw")]
    pub v729: u32,
    #[od(index = 0x22da, access = "rw")]
    pub v730: u32,
    #[od(index = 0x22db, access = "rw")]
    pub v731: u32,
    #[od(index = 0x22dc, access = "rw")]
    pub v732: u32,
    #[od(index = 0x22dd, access = "rw")]
    pub v733: u32,
    #[od(index = 0x22de, access = "rw")]
    pub v734: u32,
    #[od(index = 0x22df, access = "rw")]
    pub v735: u32,
    #[od(index = 0x22e0, access = "rw")]
    pub v736: u32,
    #[od(index = 0x22e1, access = "rw")]
    pub v737: u32,
    #[od(index = 0x22e2, access = "rw")]
    pub v738: u32,
    #[od(index = 0x22e3, access = "rw")]
    pub v739: u32,
    #[od(index = 0x22e4, access = "rw")]
    pub v740: u32,
    #[od(index = 0x22e5, access = "rw")]
    pub v741: u32,
    #[od(index = 0x22e6, access = "rw")]
    pub v742: u32,
    #[od(index = 0x22e7, access = "rw")]
    pub v743: u32,
    #[od(index = 0x22e8, access = "rw")]
    pub v744: u32,
    #[od(index = 0x22e9, access = "rw")]
    pub v745: u32,
    #[od(index = 0x22ea, access = "rw")]
    pub v746: u32,
    #[od(index = 0x22eb, access = "rw")]
    pub v747: u32,
    #[od(index = 0x22ec, access = "rw")]
    pub v748: u32,
    #[od(index = 0x22ed, access = "rw")]
    pub v749: u32,
    #[od(index = 0x22ee, access = "rw")]
    pub v750: u32,
    #[od(index = 0x22ef, access = "rw")]
    pub v751: u32,
    #[od(index = 0x22f0, access = "rw")]
    pub v752: u32,
    #[od(index = 0x22f1, access = "rw")]
    pub v753: u32,
    #[od(index = 0x22f2, access = "rw")]
    pub v754: u32,
    #[od(index = 0x22f3, access = "rw")]
    pub v755: u32,
    #[od(index = 0x22f4, access = "rw")]
    pub v756: u32,
    #[od(index = 0x22f5, access = "rw")]
    pub v757: u32,
    #[od(index = 0x22f6, access = "rw")]
    pub v758: u32,
    #[od(index = 0x22f7, access = "rw")]
    pub v759: u32,
    #[od(index = 0x22f8, access = "rw")]
    pub v760: u32,
    #[od(index = 0x22f9, access = "rw")]
    pub v761: u32,
    #[od(index = 0x22fa, access = "rw")]
    pub v762: u32,
    #[od(index = 0x22fb, access = "rw")]
    pub v763: u32,
    #[od(index = 0x22fc, access = "rw")]
    pub v764: u32,
    #[od(index = 0x22fd, access = "rw")]
    pub v765: u32,
    #[od(index = 0x22fe, access = "rw")]
    pub v766: u32,
    #[od(index = 0x22ff, access = "rw")]
    pub v767: u32,
    #[od(index = 0x2300, access = "rw")]
    pub v768: u32,
    #[od(index = 0x2301, access = "rw")]
    pub v769: u32,
    #[od(index = 0x2302, access = "rw")]
    pub v770: u32,
    #[od(index = 0x2303, access = "rw")]
    pub v771: u32,
    #[od(index = 0x2304, access = "rw")]
    pub v772: u32,
    #[od(index = 0x2305, access = "rw")]
    pub v773: u32,
    #[od(index = 0x2306, access = "rw")]
    pub v774: u32,
    #[od(index = 0x2307, access = "rw")]
    pub v775: u32,
    #[od(index = 0x2308, access = "rw")]
    pub v776: u32,
    #[od(index = 0x2309, access = "rw")]
    pub v777: u32,
    #[od(index = 0x230a, access = "rw")]
    pub v778: u32,
    #[od(index = 0x230b, access = "rw")]
    pub v779: u32,
    #[od(index = 0x230c, access = "rw")]
    pub v780: u32,
    #[od(index = 0x230d, access = "rw")]
    pub v781: u32,
    #[od(index = 0x230e, access = "rw")]
    pub v782: u32,
    #[od(index = 0x230f, access = "rw")]
    pub v783: u32,
    #[od(index = 0x2310, access = "rw")]
    pub v784: u32,
    #[od(index = 0x2311, access = "rw")]
    pub v785: u32,
    #[od(index = 0x2312, access = "rw")]
    pub v786: u32,
    #[od(index = 0x2313, access = "rw")]
    pub v787: u32,
    #[od(index = 0x2314, access = "rw")]
    pub v788: u32,
    #[od(index = 0x2315, access = "rw")]
    pub v789: u32,
    #[od(index = 0x2316, access = "rw")]
    pub v790: u32,
    #[od(index = 0x2317, access = "rw")]
    pub v791: u32,
    #[od(index = 0x2318, access = "rw")]
    pub v792: u32,
    #[od(index = 0x2319, access = "rw")]
    pub v793: u32,
    #[od(index = 0x231a, access = "rw")]
    pub v794: u32,
    #[od(index = 0x231b, access = "rw")]
    pub v795: u32,
    #[od(index = 0x231c, access = "rw")]
    pub v796: u32,
    #[od(index = 0x231d, access = "rw")]
    pub v797: u32,
    #[od(index = 0x231e, access = "rw")]
    pub v798: u32,
    #[od(index = 0x231f, access = "rw")]
    pub v799: u32,
    #[od(index = 0x2320, access = "rw")]
    pub v800: u32,
    #[od(index = 0x2321, access = "rw")]
    pub v801: u32,
    #[od(index = 0x2322, access = "rw")]
    pub v802: u32,
    #[od(index = 0x2323, access = "rw")]
    pub v803: u32,
    #[od(index = 0x2324, access = "rw")]
    pub v804: u32,
    #[od(index = 0x2325, access = "rw")]
    pub v805: u32,
    #[od(index = 0x2326, access = "rw")]
    pub v806: u32,
    #[od(index = 0x2327, access = "rw")]
    pub v807: u32,
    #[od(index = 0x2328, access = "rw")]
    pub v808: u32,
    #[od(index = 0x2329, access = "rw")]
    pub v809: u32,
    #[od(index = 0x232a, access = "rw")]
    pub v810: u32,
    #[od(index = 0x232b, access = "rw")]
    pub v811: u32,
    #[od(index = 0x232c, access = "rw")]
    pub v812: u32,
    #[od(index = 0x232d, access = "rw")]
    pub v813: u32,
    #[od(index = 0x232e, access = "rw")]
    pub v814: u32,
    #[od(index = 0x232f, access = "rw")]
    pub v815: u32,
    #[od(index = 0x2330, access = "rw")]
    pub v816: u32,
    #[od(index = 0x2331, access = "rw")]
    pub v817: u32,
    #[od(index = 0x2332, access = "rw")]
    pub v818: u32,
    #[od(index = 0x2333, access = "rw")]
    pub v819: u32,
    #[od(index = 0x2334, access = "rw")]
    pub v820: u32,
    #[od(index = 0x2335, access = "rw")]
    pub v821: u32,
    #[od(index = 0x2336, access = "rw")]
    pub v822: u32,
    #[od(index = 0x2337, access = "rw")]
    pub v823: u32,
    #[od(index = 0x2338, access = "rw")]
    pub v824: u32,
    #[od(index = 0x2339, access = "rw")]
    pub v825: u32,
    #[od(index = 0x233a, access = "rw")]
    pub v826: u32,
    #[od(index = 0x233b, access = "rw")]
    pub v827: u32,
    #[od(index = 0x233c, access = "rw")]
    pub v828: u32,
    #[od(index = 0x233d, access = "rw")]
    pub v829: u32,
    #[od(index = 0x233e, access = "rw")]
    pub v830: u32,
    #[od(index = 0x233f, access = "rw")]
    pub v831: u32,
    #[od(index = 0x2340, access = "rw")]
    pub v832: u32,
    #[od(index = 0x2341, access = "rw")]
    pub v833: u32,
    #[od(index = 0x2342, access = "rw")]
    pub v834: u32,
    #[od(index = 0x2343, access = "rw")]
    pub v835: u32,
    #[od(index = 0x2344, access = "rw")]
    pub v836: u32,
    #[od(index = 0x2345, access = "rw")]
    pub v837: u32,
    #[od(index = 0x2346, access = "rw")]
    pub v838: u32,
    #[od(index = 0x2347, access = "rw")]
    pub v839: u32,
    #[od(index = 0x2348, access = "rw")]
    pub v840: u32,
    #[od(index = 0x2349, access = "rw")]
    pub v841: u32,
    #[od(index = 0x234a, access = "rw")]
    pub v842: u32,
    #[od(index = 0x234b, access = "rw")]
    pub v843: u32,
    #[od(index = 0x234c, access = "rw")]
    pub v844: u32,
    #[od(index = 0x234d, access = "rw")]
    pub v845: u32,
    #[od(index = 0x234e, access = "rw")]
    pub v846: u32,
    #[od(index = 0x234f, access = "rw")]
    pub v847: u32,
    #[od(index = 0x2350, access = "rw")]
    pub v848: u32,
    #[od(index = 0x2351, access = "rw")]
    pub v849: u32,
    #[od(index = 0x2352, access = "rw")]
    pub v850: u32,
    #[od(index = 0x2353, access = "rw")]
    pub v851: u32,
    #[od(index = 0x2354, access = "rw")]
    pub v852: u32,
    #[od(index = 0x2355, access = "rw")]
    pub v853: u32,
    #[od(index = 0x2356, access = "rw")]
    pub v854: u32,
    #[od(index = 0x2357, access = "rw")]
    pub v855: u32,
    #[od(index = 0x2358, access = "rw")]
    pub v856: u32,
    #[od(index = 0x2359, access = "rw")]
    pub v857: u32,
    #[od(index = 0x235a, access = "rw")]
    pub v858: u32,
    #[od(index = 0x235b, access = "rw")]
    pub v859: u32,
    #[od(index = 0x235c, access = "rw")]
    pub v860: u32,
    #[od(index = 0x235d, access = "rw")]
    pub v861: u32,
    #[od(index = 0x235e, access = "rw")]
    pub v862: u32,
    #[od(index = 0x235f, access = "rw")]
    pub v863: u32,
    #[od(index = 0x2360, access = "rw")]
    pub v864: u32,
    #[od(index = 0x2361, access = "rw")]
    pub v865: u32,
    #[od(index = 0x2362, access = "rw")]
    pub v866: u32,
    #[od(index = 0x2363, access = "rw")]
    pub v867: u32,
    #[od(index = 0x2364, access = "rw")]
    pub v868: u32,
    #[od(index = 0x2365, access = "rw")]
    pub v869: u32,
    #[od(index = 0x2366, access = "rw")]
    pub v870: u32,
    #[od(index = 0x2367, access = "rw")]
    pub v871: u32,
    #[od(index = 0x2368, access = "rw")]
    pub v872: u32,
    #[od(index = 0x2369, access = "rw")]
    pub v873: u32,
    #[od(index = 0x236a, access = "rw")]
    pub v874: u32,
    #[od(index = 0x236b, access = "rw")]
    pub v875: u32,
    #[od(index = 0x236c, access = "rw")]
    pub v876: u32,
    #[od(index = 0x236d, access = "rw")]
    pub v877: u32,
    #[od(index = 0x236e, access = "rw")]
    pub v878: u32,
    #[od(index = 0x236f, access = "rw")]
    pub v879: u32,
    #[od(index = 0x2370, access = "rw")]
    pub v880: u32,
    #[od(index = 0x2371, access = "rw")]
    pub v881: u32,
    #[od(index = 0x2372, access = "rw")]
    pub v882: u32,
    #[od(index = 0x2373, access = "rw")]
    pub v883: u32,
    #[od(index = 0x2374, access = "rw")]
    pub v884: u32,
    #[od(index = 0x2375, access = "rw")]
    pub v885: u32,
    #[od(index = 0x2376, access = "rw")]
    pub v886: u32,
    #[od(index = 0x2377, access = "rw")]
    pub v887: u32,
    #[od(index = 0x2378, access = "rw")]
    pub v888: u32,
    #[od(index = 0x2379, access = "rw")]
    pub v889: u32,
    #[od(index = 0x237a, access = "rw")]
    pub v890: u32,
    #[od(index = 0x237b, access = "rw")]
    pub v891: u32,
    #[od(index = 0x237c, access = "rw")]
    pub v892: u32,
    #[od(index = 0x237d, access = "rw")]
    pub v893: u32,
    #[od(index = 0x237e, access = "rw")]
    pub v894: u32,
    #[od(index = 0x237f, access = "rw")]
    pub v895: u32,
    #[od(index = 0x2380, access = "rw")]
    pub v896: u32,
    #[od(index = 0x2381, access = "rw")]
    pub v897: u32,
    #[od(index = 0x2382, access = "rw")]
    pub v898: u32,
    #[od(index = 0x2383, access = "rw")]
    pub v899: u32,
    #[od(index = 0x2384, access = "rw")]
    pub v900: u32,
    #[od(index = 0x2385, access = "rw")]
    pub v901: u32,
    #[od(index = 0x2386, access = "rw")]
    pub v902: u32,
    #[od(index = 0x2387, access = "rw")]
    pub v903: u32,
    #[od(index = 0x2388, access = "rw")]
    pub v904: u32,
    #[od(index = 0x2389, access = "rw")]
    pub v905: u32,
    #[od(index = 0x238a, access = "rw")]
    pub v906: u32,
    #[od(index = 0x238b, access = "rw")]
    pub v907: u32,
    #[od(index = 0x238c, access = "rw")]
    pub v908: u32,
    #[od(index = 0x238d, access = "rw")]
    pub v909: u32,
    #[od(index = 0x238e, access = "rw")]
    pub v910: u32,
    #[od(index = 0x238f, access = "rw")]
    pub v911: u32,
    #[od(index = 0x2390, access = "rw")]
    pub v912: u32,
    #[od(index = 0x2391, access = "rw")]
    pub v913: u32,
    #[od(index = 0x2392, access = "rw")]
    pub v914: u32,
    #[od(index = 0x2393, access = "rw")]
    pub v915: u32,
    #[od(index = 0x2394, access = "rw")]
    pub v916: u32,
    #[od(index = 0x2395, access = "rw")]
    pub v917: u32,
    #[od(index = 0x2396, access = "rw")]
    pub v918: u32,
    #[od(index = 0x2397, access = "rw")]
    pub v919: u32,
    #[od(index = 0x2398, access = "rw")]
    pub v920: u32,
    #[od(index = 0x2399, access = "rw")]
    pub v921: u32,
    #[od(index = 0x239a, access = "rw")]
    pub v922: u32,
    #[od(index = 0x239b, access = "rw")]
    pub v923: u32,
    #[od(index = 0x239c, access = "rw")]
    pub v924: u32,
    #[od(index = 0x239d, access = "rw")]
    pub v925: u32,
    #[od(index = 0x239e, access = "rw")]
    pub v926: u32,
    #[od(index = 0x239f, access = "rw")]
    pub v927: u32,
    #[od(index = 0x23a0, access = "rw")]
    pub v928: u32,
    #[od(index = 0x23a1, access = "rw")]
    pub v929: u32,
    #[od(index = 0x23a2, access = "rw")]
    pub v930: u32,
    #[od(index = 0x23a3, access = "rw")]
    pub v931: u32,
    #[od(index = 0x23a4, access = "rw")]
    pub v932: u32,
    #[od(index = 0x23a5, access = "rw")]
    pub v933: u32,
    #[od(index = 0x23a6, access = "rw")]
    pub v934: u32,
    #[od(index = 0x23a7, access = "rw")]
    pub v935: u32,
    #[od(index = 0x23a8, access = "rw")]
    pub v936: u32,
    #[od(index = 0x23a9, access = "rw")]
    pub v937: u32,
    #[od(index = 0x23aa, access = "rw")]
    pub v938: u32,
    #[od(index = 0x23ab, access = "rw")]
    pub v939: u32,
    #[od(index = 0x23ac, access = "rw")]
    pub v940: u32,
    #[od(index = 0x23ad, access = "rw")]
    pub v941: u32,
    #[od(index = 0x23ae, access = "rw")]
    pub v942: u32,
    #[od(index = 0x23af, access = "rw")]
    pub v943: u32,
    #[od(index = 0x23b0, access = "rw")]
    pub v944: u32,
    #[od(index = 0x23b1, access = "rw")]
    pub v945: u32,
    #[od(index = 0x23b2, access = "rw")]
    pub v946: u32,
    #[od(index = 0x23b3, access = "rw")]
    pub v947: u32,
    #[od(index = 0x23b4, access = "rw")]
    pub v948: u32,
    #[od(index = 0x23b5, access = "rw")]
    pub v949: u32,
    #[od(index = 0x23b6, access = "rw")]
    pub v950: u32,
    #[od(index = 0x23b7, access = "rw")]
    pub v951: u32,
    #[od(index = 0x23b8, access = "rw")]
    pub v952: u32,
    #[od(index = 0x23b9, access = "rw")]
    pub v953: u32,
    #[od(index = 0x23ba, access = "rw")]
    pub v954: u32,
    #[od(index = 0x23bb, access = "rw")]
    pub v955: u32,
    #[od(index = 0x23bc, access = "rw")]
    pub v956: u32,
    #[od(index = 0x23bd, access = "rw")]
    pub v957: u32,
    #[od(index = 0x23be, access = "rw")]
    pub v958: u32,
    #[od(index = 0x23bf, access = "rw")]
    pub v959: u32,
    #[od(index = 0x23c0, access = "rw")]
    pub v960: u32,
    #[od(index = 0x23c1, access = "rw")]
    pub v961: u32,
    #[od(index = 0x23c2, access = "rw")]
    pub v962: u32,
    #[od(index = 0x23c3, access = "rw")]
    pub v963: u32,
    #[od(index = 0x23c4, access = "rw")]
    pub v964: u32,
    #[od(index = 0x23c5, access = "rw")]
    pub v965: u32,
    #[od(index = 0x23c6, access = "rw")]
    pub v966: u32,
    #[od(index = 0x23c7, access = "rw")]
    pub v967: u32,
    #[od(index = 0x23c8, access = "rw")]
    pub v968: u32,
    #[od(index = 0x23c9, access = "rw")]
    pub v969: u32,
    #[od(index = 0x23ca, access = "rw")]
    pub v970: u32,
    #[od(index = 0x23cb, access = "rw")]
    pub v971: u32,
    #[od(index = 0x23cc, access = "rw")]
    pub v972: u32,
    #[od(index = 0x23cd, access = "rw")]
    pub v973: u32,
    #[od(index = 0x23ce, access = "rw")]
    pub v974: u32,
    #[od(index = 0x23cf, access = "rw")]
    pub v975: u32,
    #[od(index = 0x23d0, access = "rw")]
    pub v976: u32,
    #[od(index = 0x23d1, access = "rw")]
    pub v977: u32,
    #[od(index = 0x23d2, access = "rw")]
    pub v978: u32,
    #[od(index = 0x23d3, access = "rw")]
    pub v979: u32,
    #[od(index = 0x23d4, access = "rw")]
    pub v980: u32,
    #[od(index = 0x23d5, access = "rw")]
    pub v981: u32,
    #[od(index = 0x23d6, access = "rw")]
    pub v982: u32,
    #[od(index = 0x23d7, access = "rw")]
    pub v983: u32,
    #[od(index = 0x23d8, access = "rw")]
    pub v984: u32,
    #[od(index = 0x23d9, access = "rw")]
    pub v985: u32,
    #[od(index = 0x23da, access = "rw")]
    pub v986: u32,
    #[od(index = 0x23db, access = "rw")]
    pub v987: u32,
    #[od(index = 0x23dc, access = "rw")]
    pub v988: u32,
    #[od(index = 0x23dd, access = "rw")]
    pub v989: u32,
    #[od(index = 0x23de, access = "rw")]
    pub v990: u32,
    #[od(index = 0x23df, access = "rw")]
    pub v991: u32,
    #[od(index = 0x23e0, access = "rw")]
    pub v992: u32,
    #[od(index = 0x23e1, access = "rw")]
    pub v993: u32,
    #[od(index = 0x23e2, access = "rw")]
    pub v994: u32,
    #[od(index = 0x23e3, access = "rw")]
    pub v995: u32,
    #[od(index = 0x23e4, access = "rw")]
    pub v996: u32,
    #[od(index = 0x23e5, access = "rw")]
    pub v997: u32,
    #[od(index = 0x23e6, access = "rw")]
    pub v998: u32,
    #[od(index = 0x23e7, access = "rw")]
    pub v999: u32,
}
